#include "link/sim_link.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace cellctl::link {
namespace {

using namespace std::chrono_literals;

std::vector<std::uint8_t> read_all(Link& l) {
  std::array<std::uint8_t, 64> buf{};
  auto r = l.read(buf);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count)};
}

TEST(LineFormat, CharacterTimes) {
  EXPECT_EQ(line_8n1(38400).bits_per_char(), 10u);
  EXPECT_EQ(line_8e1(1'500'000).bits_per_char(), 11u);
  EXPECT_EQ(line_8n1(38400).char_time(), 260416ns);
  EXPECT_EQ(line_8n1(38400).describe(), "38400 8N1");
  EXPECT_EQ(line_8e1(19200).describe(), "19200 8E1");
}

TEST(SimLink, DeliversEachByteAfterItsCharacterTime) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(9600));  // 1041666 ns per character
  const std::array<std::uint8_t, 3> tx{1, 2, 3};
  ASSERT_EQ(sim.master().write(tx).count, 3u);

  EXPECT_TRUE(read_all(sim.device()).empty()) << "nothing arrives instantly";
  clock.advance(1041666ns - 1ns);
  EXPECT_TRUE(read_all(sim.device()).empty());
  clock.advance(1ns);
  EXPECT_EQ(read_all(sim.device()), (std::vector<std::uint8_t>{1}));
  clock.advance(2 * 1041666ns);
  EXPECT_EQ(read_all(sim.device()), (std::vector<std::uint8_t>{2, 3}));
  EXPECT_TRUE(read_all(sim.master()).empty()) << "nothing echoes back";
}

TEST(SimLink, BackToBackWritesQueueOnTheLine) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(10000));  // 1 ms per character
  const std::array<std::uint8_t, 1> a{0xaa};
  ASSERT_EQ(sim.master().write(a).count, 1u);
  ASSERT_EQ(sim.master().write(a).count, 1u);  // line busy: starts after the first
  EXPECT_EQ(sim.next_delivery(), TimePoint{} + 1ms);
  clock.advance(1ms);
  EXPECT_EQ(read_all(sim.device()).size(), 1u);
  EXPECT_EQ(sim.next_delivery(), TimePoint{} + 2ms);
  clock.advance(1ms);
  EXPECT_EQ(read_all(sim.device()).size(), 1u);
  EXPECT_FALSE(sim.next_delivery().has_value());
}

TEST(SimLink, DirectionsAreIndependent) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(10000));
  const std::array<std::uint8_t, 1> a{1};
  const std::array<std::uint8_t, 1> b{2};
  ASSERT_EQ(sim.master().write(a).count, 1u);
  ASSERT_EQ(sim.device().write(b).count, 1u);
  clock.advance(1ms);
  EXPECT_EQ(read_all(sim.device()), (std::vector<std::uint8_t>{1}));
  EXPECT_EQ(read_all(sim.master()), (std::vector<std::uint8_t>{2}));
}

TEST(SimLink, ACutCableLosesBytes) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(38400));
  sim.set_cut(true);
  const std::array<std::uint8_t, 2> a{1, 2};
  EXPECT_EQ(sim.master().write(a).count, 2u);
  clock.advance(10ms);
  EXPECT_TRUE(read_all(sim.device()).empty());
  sim.set_cut(false);
  ASSERT_EQ(sim.master().write(a).count, 2u);
  clock.advance(10ms);
  EXPECT_EQ(read_all(sim.device()).size(), 2u);
}

}  // namespace
}  // namespace cellctl::link

#include "link/fault_injecting_link.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cerrno>
#include <numeric>
#include <vector>

#include "link/sim_link.hpp"

namespace cellctl::link {
namespace {

using namespace std::chrono_literals;

// A session's end (wrapped) and a device's end of one simulated 9600-baud line, on a virtual clock.
struct Line {
  VirtualClock clock;
  SimLink sim{clock, line_8n1(9600)};
  FaultInjectingLink faulty{sim.master(), clock, 7};
  Link& session = faulty;
  Link& device = sim.device();

  // Everything that arrives at `to` in the next `span` (the line is read every millisecond).
  std::vector<std::uint8_t> collect(Link& to, Duration span) {
    std::vector<std::uint8_t> out;
    std::array<std::uint8_t, 64> buf{};
    for (const auto end = clock.now() + span; clock.now() < end; clock.advance(1ms)) {
      const auto r = to.read(buf);
      EXPECT_TRUE(r.ok());
      out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count));
    }
    return out;
  }
};

std::vector<std::uint8_t> counting(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  std::iota(v.begin(), v.end(), std::uint8_t{0x40});
  return v;
}

TEST(FaultInjectingLink, PassesEverythingOutsideItsWindows) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::silent}, TimePoint{} + 1s, TimePoint{} + 2s));
  const auto bytes = counting(8);
  ASSERT_EQ(line.session.write(bytes).count, 8u);
  EXPECT_EQ(line.collect(line.device, 20ms), bytes);
  ASSERT_EQ(line.device.write(bytes).count, 8u);
  EXPECT_EQ(line.collect(line.session, 20ms), bytes);
  EXPECT_EQ(line.faulty.describe(), "sim:master") << "it names the link it wraps";
}

TEST(FaultInjectingLink, SilentCarriesNothingEitherWayUntilItEnds) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::silent}, TimePoint{}, TimePoint{} + 100ms));
  const auto bytes = counting(4);
  EXPECT_EQ(line.session.write(bytes).count, 4u) << "the port takes the bytes: it cannot know";
  ASSERT_EQ(line.device.write(bytes).count, 4u);
  EXPECT_TRUE(line.collect(line.device, 50ms).empty());
  EXPECT_TRUE(line.collect(line.session, 50ms).empty()) << "the device's reply is lost on the line";
  EXPECT_EQ(line.faulty.counters().lost, 8u);

  ASSERT_EQ(line.session.write(bytes).count, 4u);
  EXPECT_EQ(line.collect(line.device, 20ms), bytes) << "the line carries again after the window";
}

TEST(FaultInjectingLink, DisconnectReportsThePortGoneAsATtyDoes) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::disconnect}, TimePoint{} + 10ms, TimePoint{} + 60ms));
  line.clock.advance(10ms);
  const auto bytes = counting(4);
  const auto w = line.session.write(bytes);
  EXPECT_EQ(w.status, IoStatus::closed);
  EXPECT_EQ(w.error_number, EIO);
  ASSERT_EQ(line.device.write(bytes).count, 4u);
  line.clock.advance(20ms);
  std::array<std::uint8_t, 16> buf{};
  const auto r = line.session.read(buf);
  EXPECT_EQ(r.status, IoStatus::closed);
  EXPECT_EQ(r.error_number, EIO);
  EXPECT_EQ(r.count, 0u);

  line.clock.advance(30ms);  // plugged in again: what the device sent meanwhile is gone
  EXPECT_TRUE(line.collect(line.session, 20ms).empty());
  ASSERT_EQ(line.session.write(bytes).count, 4u);
  EXPECT_EQ(line.collect(line.device, 20ms), bytes);
}

TEST(FaultInjectingLink, CorruptFlipsOneBitInEveryFourthByteBothWays) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::corrupt}, TimePoint{}));
  const auto bytes = counting(16);
  ASSERT_EQ(line.session.write(bytes).count, 16u);
  ASSERT_EQ(line.device.write(bytes).count, 16u);
  for (const auto& got : {line.collect(line.device, 40ms), line.collect(line.session, 40ms)}) {
    ASSERT_EQ(got.size(), bytes.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      const auto diff = static_cast<unsigned>(got[i] ^ bytes[i]);
      const bool hit = i % FaultInjectingLink::kCorruptStride == 0;
      EXPECT_EQ(__builtin_popcount(diff), hit ? 1 : 0) << "byte " << i;
    }
  }
  EXPECT_EQ(line.faulty.counters().flipped, 8u);
}

TEST(FaultInjectingLink, GarbageMixesSeededRandomBytesIntoTheTraffic) {
  const auto received = [](std::uint32_t seed) {
    VirtualClock clock;
    SimLink sim(clock, line_8n1(9600));
    FaultInjectingLink faulty(sim.master(), clock, seed);
    EXPECT_TRUE(faulty.schedule({LinkFaultKind::garbage}, TimePoint{}, TimePoint{} + 50ms));
    const auto bytes = counting(10);
    EXPECT_EQ(sim.device().write(bytes).count, 10u);
    std::vector<std::uint8_t> out;
    std::array<std::uint8_t, 64> buf{};
    for (int ms = 0; ms < 60; ++ms, clock.advance(1ms)) {
      const auto r = faulty.read(buf);
      out.insert(out.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count));
    }
    EXPECT_GT(faulty.counters().injected, 0u);
    EXPECT_EQ(out.size(), 10u + faulty.counters().injected) << "the real bytes all pass, among the noise";
    return out;
  };
  const auto a = received(11);
  EXPECT_EQ(received(11), a) << "the same seed makes the same noise";
  EXPECT_NE(received(12), a);
}

TEST(FaultInjectingLink, DelayHoldsRepliesBackAndKeepsTheirOrderAfterTheWindow) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::delay, 300ms}, TimePoint{}, TimePoint{} + 100ms));
  const auto first = counting(2);
  ASSERT_EQ(line.device.write(first).count, 2u);  // arrives at 2.08 ms, delivered from 302.08 ms on
  EXPECT_TRUE(line.collect(line.session, 150ms).empty());
  const std::array<std::uint8_t, 1> later{0x99};
  ASSERT_EQ(line.device.write(later).count, 1u);  // after the window: not delayed, but behind the first
  ASSERT_EQ(line.session.write(first).count, 2u) << "requests are not delayed";
  EXPECT_EQ(line.collect(line.device, 10ms), first);
  const auto got = line.collect(line.session, 150ms);  // up to 310 ms
  EXPECT_EQ(got, (std::vector<std::uint8_t>{0x40, 0x41, 0x99}));
  EXPECT_EQ(line.faulty.counters().delayed, 2u);
}

TEST(FaultInjectingLink, DelayDeliversAtTheDelayAfterArrival) {
  Line line;
  ASSERT_TRUE(line.faulty.schedule({LinkFaultKind::delay, 50ms}, TimePoint{}));
  const std::array<std::uint8_t, 1> one{0x5A};
  ASSERT_EQ(line.device.write(one).count, 1u);  // on the wire for 1.04 ms
  std::array<std::uint8_t, 4> buf{};
  Duration arrived{};
  for (int ms = 0; ms < 100 && arrived == Duration{}; ++ms, line.clock.advance(1ms))
    if (line.session.read(buf).count == 1) arrived = line.clock.now().time_since_epoch();
  // Seen by the wrapper at the first read after 1.04 ms (2 ms), delivered 50 ms after that.
  EXPECT_EQ(arrived, 52ms);
}

// A link whose port is really gone: the wrapper must pass that on, whatever fault it plays.
class GoneLink final : public Link {
 public:
  IoResult read(std::span<std::uint8_t>) override { return {0, IoStatus::failed, ENXIO}; }
  IoResult write(std::span<const std::uint8_t>) override { return {0, IoStatus::failed, ENXIO}; }
  [[nodiscard]] std::string describe() const override { return "gone"; }
};

TEST(FaultInjectingLink, NeverHidesARealFailureOfTheLinkItWraps) {
  VirtualClock clock;
  GoneLink gone;
  for (const auto kind : {LinkFaultKind::silent, LinkFaultKind::disconnect, LinkFaultKind::corrupt,
                          LinkFaultKind::garbage, LinkFaultKind::delay}) {
    FaultInjectingLink faulty(gone, clock);
    ASSERT_TRUE(faulty.schedule({kind, 10ms}, TimePoint{}));
    std::array<std::uint8_t, 8> buf{};
    const auto r = faulty.read(buf);
    EXPECT_EQ(r.status, IoStatus::failed) << to_string(kind);
    EXPECT_EQ(r.error_number, ENXIO) << to_string(kind);
    if (kind != LinkFaultKind::silent && kind != LinkFaultKind::disconnect) {
      EXPECT_EQ(faulty.write(buf).status, IoStatus::failed) << to_string(kind);
    }
  }
}

TEST(FaultInjectingLink, TheFirstOpenWindowActsAndAFullScheduleRefusesMore) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(9600));
  FaultInjectingLink faulty(sim.master(), clock);
  ASSERT_TRUE(faulty.schedule({LinkFaultKind::corrupt}, TimePoint{} + 1s, TimePoint{} + 3s));
  ASSERT_TRUE(faulty.schedule({LinkFaultKind::delay, 5ms}, TimePoint{} + 2s));
  EXPECT_FALSE(faulty.active(TimePoint{}));
  EXPECT_EQ(faulty.active(TimePoint{} + 2s)->kind, LinkFaultKind::corrupt);
  EXPECT_EQ(faulty.active(TimePoint{} + 3s)->kind, LinkFaultKind::delay);
  EXPECT_EQ(faulty.active(TimePoint{} + 3s)->delay, 5ms);
  for (std::size_t i = 2; i < FaultInjectingLink::kMaxWindows; ++i)
    EXPECT_TRUE(faulty.schedule({LinkFaultKind::silent}, TimePoint{} + 10s));
  EXPECT_FALSE(faulty.schedule({LinkFaultKind::silent}, TimePoint{} + 10s));
}

}  // namespace
}  // namespace cellctl::link

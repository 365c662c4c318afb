#include "link/tracing_link.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "link/sim_link.hpp"

namespace cellctl::link {
namespace {

using namespace std::chrono_literals;

struct Record {
  TimePoint at;
  std::string link;
  Direction dir;
  std::vector<std::uint8_t> bytes;
};

class CollectingSink final : public TraceSink {
 public:
  void record(TimePoint at, std::string_view link, Direction dir,
              std::span<const std::uint8_t> bytes) override {
    records.push_back({at, std::string(link), dir, {bytes.begin(), bytes.end()}});
  }
  std::vector<Record> records;
};

TEST(TracingLink, OneRecordPerTelegramEachWay) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(38400));
  CollectingSink sink;
  TracingLink traced(sim.master(), clock, sink, "scu");

  const std::array<std::uint8_t, 5> ro{0x52, 0x4f, 0x00, 0x5c, 0x2d};
  ASSERT_EQ(traced.write(ro).count, 5u);
  ASSERT_EQ(sink.records.size(), 1u);
  EXPECT_EQ(sink.records[0].dir, Direction::tx);
  EXPECT_EQ(sink.records[0].link, "scu");

  // The reply arrives in pieces; a quiet poll closes the run into one RX record.
  const std::array<std::uint8_t, 5> reply{0x52, 0x4f, 0x06, 0x00, 0x00};
  ASSERT_EQ(sim.device().write(reply).count, 5u);
  std::array<std::uint8_t, 16> buf{};
  clock.advance(600us);  // two characters
  EXPECT_EQ(traced.read(buf).count, 2u);
  clock.advance(1ms);
  EXPECT_EQ(traced.read(buf).count, 3u);
  EXPECT_EQ(sink.records.size(), 1u) << "still receiving";
  EXPECT_EQ(traced.read(buf).count, 0u);
  ASSERT_EQ(sink.records.size(), 2u);
  EXPECT_EQ(sink.records[1].dir, Direction::rx);
  EXPECT_EQ(sink.records[1].bytes, std::vector<std::uint8_t>(reply.begin(), reply.end()));
  EXPECT_EQ(sink.records[1].at, TimePoint{} + 600us) << "stamped when the run started";
}

TEST(TracingLink, PassesBytesThroughUnchanged) {
  VirtualClock clock;
  SimLink sim(clock, line_8n1(38400));
  CollectingSink sink;
  TracingLink traced(sim.device(), clock, sink, "dev");
  const std::array<std::uint8_t, 3> a{1, 2, 3};
  ASSERT_EQ(sim.master().write(a).count, 3u);
  clock.advance(1s);
  std::array<std::uint8_t, 8> buf{};
  ASSERT_EQ(traced.read(buf).count, 3u);
  EXPECT_EQ(buf[2], 3);
}

}  // namespace
}  // namespace cellctl::link

#include "link/tracing_link.hpp"

#include <fmt/chrono.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <array>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "link/sim_link.hpp"
#include "support/allocation_counter.hpp"

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

// The "trace" logger the CLI creates, writing into a list of lines the test reads under a lock.
class LineSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  std::vector<std::string> lines() {
    std::lock_guard lock(mutex_);
    return lines_;
  }

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    lines_.emplace_back(msg.payload.begin(), msg.payload.end());
  }
  void flush_() override {}

 private:
  std::vector<std::string> lines_;
};

struct TraceLogger {
  TraceLogger() : sink(std::make_shared<LineSink>()) {
    spdlog::register_logger(std::make_shared<spdlog::logger>("trace", sink));
  }
  ~TraceLogger() { spdlog::drop("trace"); }
  std::shared_ptr<LineSink> sink;
};

TEST(LogTraceSink, TheCallersThreadOnlyQueuesTheWriterFormats) {
  TraceLogger logger;
  VirtualClock clock(TimePoint{} + 1500ms);
  SimLink sim(clock, line_8n1(38400));
  LogTraceSink sink(wire::WhenFull::drop_and_count, LogTraceSink::Writer::manual);
  TracingLink traced(sim.master(), clock, sink, "scu");
  const std::array<std::uint8_t, 5> ro{0x52, 0x4f, 0x00, 0x5c, 0x2d};
  const std::array<std::uint8_t, 3> reply{0x52, 0x4f, 0x06};
  ASSERT_EQ(sim.device().write(reply).count, 3u);
  std::array<std::uint8_t, 16> buf{};

  const std::size_t before = cellctl::testing::thread_allocation_count();
  ASSERT_EQ(traced.write(ro).count, 5u);
  clock.advance(1ms);  // the reply is on the line
  ASSERT_EQ(traced.read(buf).count, 3u);
  ASSERT_EQ(traced.read(buf).count, 0u);  // closes the RX run
  const std::size_t after = cellctl::testing::thread_allocation_count();

  EXPECT_EQ(after, before) << "no allocation on the caller's thread";
  EXPECT_TRUE(logger.sink->lines().empty()) << "nothing formatted or logged before the writer drains";
  EXPECT_EQ(sink.drain(), 2u);
  const auto lines = logger.sink->lines();
  ASSERT_EQ(lines.size(), 2u);
  // Without a run's start, times count from the first telegram; then the wall-clock time.
  EXPECT_THAT(lines[0], ::testing::MatchesRegex(
                            "   0\\.000000 s [0-9]{2}:[0-9]{2}:[0-9]{2}\\.[0-9]{6} scu TX 52 4f 00 5c 2d"));
  EXPECT_THAT(lines[1], ::testing::MatchesRegex("   0\\.001000 s [0-9:.]{15} scu RX 52 4f 06"));
}

TEST(LogTraceSink, TimesCountFromTheRunsStartAndTellTheWallClock) {
  TraceLogger logger;
  VirtualClock clock(TimePoint{} + 1500ms);
  SimLink sim(clock, line_8n1(38400));
  LogTraceSink sink(wire::WhenFull::drop_and_count, LogTraceSink::Writer::manual);
  TracingLink traced(sim.master(), clock, sink, "scu");
  sink.start_clock(TimePoint{} + 1000ms);  // the run started half a second before
  const auto wall = std::chrono::system_clock::now();
  const std::array<std::uint8_t, 2> ro{0x52, 0x4f};
  ASSERT_EQ(traced.write(ro).count, 2u);
  EXPECT_EQ(sink.drain(), 1u);
  const auto lines = logger.sink->lines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].substr(0, 14), "   0.500000 s ");
  // The wall clock half a second after start_clock (this test's own reading, to the second).
  const auto expected = std::chrono::system_clock::to_time_t(wall + 500ms);
  const auto shown = fmt::format("{:%H:%M:%S}", fmt::localtime(expected));
  const auto one_later = fmt::format("{:%H:%M:%S}", fmt::localtime(expected + 1));
  EXPECT_TRUE(lines[0].substr(14, 8) == shown || lines[0].substr(14, 8) == one_later) << lines[0];
}

TEST(LogTraceSink, AFullRingDropsAndTheWriterSaysHowMany) {
  TraceLogger logger;
  LogTraceSink sink(wire::WhenFull::drop_and_count, LogTraceSink::Writer::manual);
  const std::array<std::uint8_t, 1> b{0x01};
  for (int i = 0; i < 520; ++i) sink.record(TimePoint{}, "enc", Direction::tx, b);
  EXPECT_EQ(sink.dropped(), 8u);  // the ring holds 512
  EXPECT_EQ(sink.drain(), 512u);
  const auto lines = logger.sink->lines();
  ASSERT_EQ(lines.size(), 513u);
  EXPECT_EQ(lines.back(), "8 trace records dropped: the writer fell behind the links");
}

TEST(LogTraceSink, ALongRunIsSplitIntoRecords) {
  TraceLogger logger;
  LogTraceSink sink(wire::WhenFull::drop_and_count, LogTraceSink::Writer::manual);
  std::array<std::uint8_t, TraceRecord::kMaxBytes * 2 + 3> run{};
  sink.record(TimePoint{}, "a-link-name-longer-than-twenty-four", Direction::rx, run);
  EXPECT_EQ(sink.drain(), 3u);
  const auto lines = logger.sink->lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_THAT(lines[2], ::testing::EndsWith(" a-link-name-longer-than- RX 00 00 00"));
}

TEST(LogTraceSink, WaitingForTheWriterLosesNothing) {
  TraceLogger logger;
  {
    LogTraceSink sink(wire::WhenFull::wait);
    const std::array<std::uint8_t, 1> b{0x01};
    for (int i = 0; i < 5000; ++i) sink.record(TimePoint{}, "enc", Direction::tx, b);
    EXPECT_EQ(sink.dropped(), 0u);
  }  // the writer stops and writes the rest
  EXPECT_EQ(logger.sink->lines().size(), 5000u);
}

TEST(LogTraceSink, TheWriterThreadWritesWithoutADrainCall) {
  TraceLogger logger;
  LogTraceSink sink;
  const std::array<std::uint8_t, 2> b{0xab, 0xcd};
  sink.record(TimePoint{}, "spindle", Direction::tx, b);
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (logger.sink->lines().empty() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(1ms);
  const auto lines = logger.sink->lines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], ::testing::MatchesRegex("   0\\.000000 s [0-9:.]{15} spindle TX ab cd"));
}

}  // namespace
}  // namespace cellctl::link

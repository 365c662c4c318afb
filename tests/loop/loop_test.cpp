#include "loop/loop.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "support/allocation_counter.hpp"

namespace cellctl::loop {
namespace {

using namespace std::chrono_literals;

const link::TimePoint kStart{100s};

// Wakes `late` after every deadline: a stand-in for a real scheduler's latency, in virtual time.
class LateWaiter final : public CycleWaiter {
 public:
  LateWaiter(link::VirtualClock& clock, link::Duration late) : clock_(clock), late_(late) {}
  void wait_until(link::TimePoint deadline) noexcept override { clock_.advance_to(deadline + late_); }

 private:
  link::VirtualClock& clock_;
  link::Duration late_;
};

TEST(Loop, RejectsANonPositivePeriod) {
  link::VirtualClock clock;
  VirtualWaiter waiter(clock);
  EXPECT_THROW(Loop(clock, waiter, 0ns), std::invalid_argument);
}

TEST(Loop, DeadlinesAreAbsoluteNoDriftAfterAMillionCycles) {
  link::VirtualClock clock(kStart);
  VirtualWaiter waiter(clock);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  std::uint64_t off_grid = 0;
  link::TimePoint last{};
  // Every body computes for 370 us: a relative sleep would drift by 370 s over the run.
  loop.run(
      [&](link::TimePoint now, std::uint64_t cycle) {
        if (now != kStart + 1ms * static_cast<std::int64_t>(cycle)) ++off_grid;
        last = now;
        clock.advance(370us);
      },
      stop, 1'000'000);
  EXPECT_EQ(loop.stats().cycles, 1'000'000u);
  EXPECT_EQ(off_grid, 0u);
  EXPECT_EQ(last, kStart + 999'999ms);
  EXPECT_EQ(loop.stats().overrun_cycles, 0u);
  EXPECT_EQ(loop.stats().period_error.max(), 0ns);
  EXPECT_EQ(loop.stats().jitter.max(), 0ns);
}

TEST(Loop, OverrunCountsMissedDeadlinesAndSkipsAheadOnTheGrid) {
  link::VirtualClock clock(kStart);
  VirtualWaiter waiter(clock);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  std::vector<link::TimePoint> starts;
  starts.reserve(10);
  loop.run(
      [&](link::TimePoint now, std::uint64_t cycle) {
        starts.push_back(now);
        if (cycle == 3) clock.advance(3500us);  // 3.5 periods
      },
      stop, 6);
  EXPECT_EQ(loop.stats().overrun_cycles, 1u);
  EXPECT_EQ(loop.stats().missed_deadlines, 3u);  // 4, 5 and 6 ms: no catch-up burst
  ASSERT_EQ(starts.size(), 6u);
  EXPECT_EQ(starts[3], kStart + 3ms);
  EXPECT_EQ(starts[4], kStart + 7ms);  // back on the grid, first deadline after the overrun
  EXPECT_EQ(starts[5], kStart + 8ms);
  EXPECT_EQ(loop.stats().period_error.max(), 3ms);  // one 4 ms period
}

TEST(Loop, StageTimesAccountForEachStage) {
  link::VirtualClock clock(kStart);
  VirtualWaiter waiter(clock);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  loop.run(
      [&](link::TimePoint, std::uint64_t cycle) {
        {
          const auto t = loop.time_stage(index(ControlStage::read_sessions));
          clock.advance(100us);
        }
        clock.advance(50us);  // between stages: not counted
        {
          const auto t = loop.time_stage(index(ControlStage::supervisor));
          clock.advance(cycle == 9 ? 400us : 250us);
        }
      },
      stop, 10);
  const StageTimes& s = loop.stages();
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s.name(0), "read sessions");
  EXPECT_EQ(s.histogram(index(ControlStage::read_sessions)).total(), 1000us);
  EXPECT_EQ(s.histogram(index(ControlStage::read_sessions)).count(), 10u);
  EXPECT_EQ(s.histogram(index(ControlStage::supervisor)).total(), 9 * 250us + 400us);
  EXPECT_EQ(s.histogram(index(ControlStage::supervisor)).max(), 400us);
  EXPECT_EQ(s.histogram(index(ControlStage::monitor)).count(), 0u);
  const std::string text = loop.summary();
  EXPECT_NE(text.find("stage supervisor"), std::string::npos) << text;
  EXPECT_NE(text.find("max 400.0 us"), std::string::npos) << text;
}

TEST(Loop, CustomStageListIsValidated) {
  link::VirtualClock clock;
  VirtualWaiter waiter(clock);
  const std::array<std::string_view, 2> two{"sense", "act"};
  EXPECT_EQ(Loop(clock, waiter, 1ms, two).stages().name(1), "act");
  const std::array<std::string_view, 9> nine{"a", "b", "c", "d", "e", "f", "g", "h", "i"};
  EXPECT_THROW(Loop(clock, waiter, 1ms, nine), std::invalid_argument);
  const std::array<std::string_view, 1> unnamed{""};
  EXPECT_THROW(Loop(clock, waiter, 1ms, unnamed), std::invalid_argument);
}

TEST(Loop, StopFlagEndsAtACycleBoundary) {
  link::VirtualClock clock(kStart);
  VirtualWaiter waiter(clock);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  int bodies = 0;
  int completed = 0;
  loop.run(
      [&](link::TimePoint, std::uint64_t cycle) {
        ++bodies;
        if (cycle == 5) stop = true;  // e.g. Ctrl-C arriving mid-cycle
        clock.advance(200us);
        ++completed;  // the cycle in progress still completes
      },
      stop);
  EXPECT_EQ(bodies, 6);
  EXPECT_EQ(completed, 6);
  EXPECT_EQ(loop.stats().cycles, 6u);
  EXPECT_EQ(clock.now(), kStart + 5ms + 200us);  // did not wait for another deadline
}

TEST(Loop, WakeUpJitterIsMeasuredAgainstTheDeadline) {
  link::VirtualClock clock(kStart);
  LateWaiter waiter(clock, 30us);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  std::vector<link::TimePoint> starts;
  starts.reserve(100);
  loop.run([&](link::TimePoint now, std::uint64_t) { starts.push_back(now); }, stop, 100);
  EXPECT_EQ(loop.stats().jitter.max(), 30us);
  EXPECT_EQ(loop.stats().jitter.percentile(0.5), 30us);
  EXPECT_EQ(starts.back(), kStart + 99ms + 30us);   // lateness does not accumulate
  EXPECT_EQ(loop.stats().period_error.max(), 0ns);  // late, but steadily
  EXPECT_NE(loop.summary().find("p99 / period 3.00 %"), std::string::npos) << loop.summary();
}

TEST(Loop, RunDoesNotAllocate) {
  link::VirtualClock clock(kStart);
  VirtualWaiter waiter(clock);
  Loop loop(clock, waiter, 1ms);
  std::atomic<bool> stop{false};
  const std::size_t before = testing::allocation_count();
  loop.run(
      [&](link::TimePoint, std::uint64_t cycle) {
        for (std::size_t s = 0; s < kControlStages.size(); ++s) {
          const auto t = loop.time_stage(s);
          clock.advance(link::Duration{static_cast<std::int64_t>(1000 + cycle % 7000)});
        }
        if (cycle % 1000 == 999) clock.advance(2500us);  // overruns too
      },
      stop, 20'000);
  EXPECT_EQ(testing::allocation_count() - before, 0u);
  EXPECT_GT(loop.stats().missed_deadlines, 0u);
}

// Real time, so bounds with stated margins. Deadlines are absolute: three that have passed return
// at once, together well inside 500 ms even on a loaded two-core machine (a waiter that took the
// deadline for a relative sleep would sleep for the whole uptime); one 30 ms ahead is never
// returned from early (a lower bound holds under any load).
TEST(MonotonicWaiter, ReturnsAtOnceForAPassedDeadlineAndNotBeforeAFutureOne) {
  link::MonotonicClock clock;
  MonotonicWaiter waiter;
  const link::TimePoint start = clock.now();
  waiter.wait_until(start - 1ms);
  waiter.wait_until(start - 10s);
  waiter.wait_until(link::TimePoint{});  // the clock's origin
  EXPECT_LT(clock.now() - start, 500ms);

  const link::TimePoint ahead = clock.now() + 30ms;
  waiter.wait_until(ahead);
  EXPECT_GE(clock.now(), ahead);
}

}  // namespace
}  // namespace cellctl::loop

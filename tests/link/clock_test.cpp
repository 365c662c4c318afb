#include "link/clock.hpp"

#include <gtest/gtest.h>

#include <ctime>
#include <thread>

namespace cellctl::link {
namespace {

using namespace std::chrono_literals;

TEST(VirtualClock, MovesOnlyWhenTold) {
  VirtualClock c;
  const auto t0 = c.now();
  EXPECT_EQ(c.now(), t0);
  c.advance(1500us);
  EXPECT_EQ(c.now() - t0, 1500us);
  c.advance_to(t0);  // backwards is ignored
  EXPECT_EQ(c.now() - t0, 1500us);
  c.advance_to(t0 + 2ms);
  EXPECT_EQ(c.now() - t0, 2ms);
}

TimePoint clock_monotonic() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return TimePoint{std::chrono::seconds{ts.tv_sec} + std::chrono::nanoseconds{ts.tv_nsec}};
}

// MonotonicClock is CLOCK_MONOTONIC itself, origin included: loop::MonotonicWaiter hands its time
// points to clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME) unconverted. Another clock (the wall
// clock, or one counting from the program's start) falls outside the bracket.
TEST(MonotonicClock, ReadsClockMonotonicWithItsOrigin) {
  MonotonicClock c;
  for (int i = 0; i < 100; ++i) {
    const auto before = clock_monotonic();
    const auto t = c.now();
    const auto after = clock_monotonic();
    ASSERT_LE(before, t);
    ASSERT_LE(t, after);
  }
}

// It moves with real time: after a 20 ms sleep it has advanced at least 20 ms (a lower bound holds
// on a loaded machine; no upper bound is asserted).
TEST(MonotonicClock, AdvancesWithRealTime) {
  MonotonicClock c;
  const auto t0 = c.now();
  std::this_thread::sleep_for(20ms);
  EXPECT_GE(c.now() - t0, 20ms);
}

TEST(Milliseconds, ConvertBothWaysWithoutTruncating) {
  EXPECT_DOUBLE_EQ(to_milliseconds(1500us), 1.5);
  EXPECT_DOUBLE_EQ(to_milliseconds(-2ms), -2.0);
  EXPECT_EQ(milliseconds(2.5), 2500us);
  EXPECT_EQ(milliseconds(0.3), 300us);  // 0.3 is 0.29999… in binary: rounded, not cut to 299999 ns
  EXPECT_EQ(milliseconds(to_milliseconds(123456789ns)), 123456789ns);
}

}  // namespace
}  // namespace cellctl::link

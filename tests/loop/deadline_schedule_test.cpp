#include "loop/deadline_schedule.hpp"

#include <gtest/gtest.h>

namespace cellctl::loop {
namespace {

using namespace std::chrono_literals;
const link::TimePoint t0{10s};

TEST(NextDeadline, InTimeKeepsTheGrid) {
  EXPECT_EQ(next_deadline(t0, t0 + 300us, 1ms).deadline, t0 + 1ms);
  EXPECT_EQ(next_deadline(t0, t0 + 300us, 1ms).missed, 0u);
  EXPECT_EQ(next_deadline(t0, t0 + 1ms, 1ms).missed, 0u);  // ending on the deadline is in time
}

TEST(NextDeadline, OverrunSkipsToTheFirstFutureGridPoint) {
  const NextDeadline n = next_deadline(t0, t0 + 3500us, 1ms);
  EXPECT_EQ(n.missed, 3u);
  EXPECT_EQ(n.deadline, t0 + 4ms);
  const NextDeadline just = next_deadline(t0, t0 + 1ms + 1ns, 1ms);
  EXPECT_EQ(just.missed, 1u);
  EXPECT_EQ(just.deadline, t0 + 2ms);
  const NextDeadline exact = next_deadline(t0, t0 + 2ms, 1ms);
  EXPECT_EQ(exact.missed, 1u);
  EXPECT_EQ(exact.deadline, t0 + 2ms);
}

}  // namespace
}  // namespace cellctl::loop

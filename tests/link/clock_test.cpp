#include "link/clock.hpp"

#include <gtest/gtest.h>

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

TEST(MonotonicClock, NeverRunsBackwards) {
  MonotonicClock c;
  auto prev = c.now();
  for (int i = 0; i < 1000; ++i) {
    const auto t = c.now();
    ASSERT_GE(t, prev);
    prev = t;
  }
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

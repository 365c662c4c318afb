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

}  // namespace
}  // namespace cellctl::link

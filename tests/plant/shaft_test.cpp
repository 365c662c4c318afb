#include "plant/shaft.hpp"

#include <gtest/gtest.h>

namespace cellctl::plant {
namespace {

TEST(Shaft, FollowsTheAxisWithSlipAndOffset) {
  double axis = 0.0;
  Shaft s({.mm_per_revolution = 4.0, .slip = 0.0, .offset_revolutions = 10.0}, [&] { return axis; });
  EXPECT_DOUBLE_EQ(s.revolutions(), 10.0);
  axis = 8.0;
  EXPECT_DOUBLE_EQ(s.revolutions(), 12.0);
  s.set_slip(0.5);
  EXPECT_DOUBLE_EQ(s.revolutions(), 11.0);
}

}  // namespace
}  // namespace cellctl::plant

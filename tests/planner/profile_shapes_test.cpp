#include "planner/profile_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cellctl::planner {
namespace {

// Durations below are the textbook closed forms of the symmetric 7-segment profile, not re-derived
// from the implementation's intermediate variables.
TEST(RestToRest, LongMoveReachesBothLimits) {
  const double d = 10.0, v = 1.0, a = 2.0, j = 10.0;
  const JerkProfile p = rest_to_rest(d, {v, a, j});
  EXPECT_NEAR(p.duration(), d / v + v / a + a / j, 1e-12);  // 10.7 s
  EXPECT_EQ(p.size(), 7u);
  EXPECT_NEAR(p.end().position, d, 1e-12);
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-12);
  EXPECT_NEAR(p.end().acceleration, 0.0, 1e-12);
  EXPECT_NEAR(p.at(p.duration() / 2).velocity, v, 1e-12);  // cruising in the middle
}

TEST(RestToRest, VelocityLimitReachedWithoutAccelerationLimit) {
  const double d = 10.0, v = 1.0, a = 10.0, j = 10.0;  // v < a^2/j: the ramp has no plateau
  const JerkProfile p = rest_to_rest(d, {v, a, j});
  EXPECT_NEAR(p.duration(), d / v + 2.0 * std::sqrt(v / j), 1e-12);
  EXPECT_EQ(p.size(), 5u);
  EXPECT_NEAR(p.end().position, d, 1e-12);
}

TEST(RestToRest, ShortMoveNeverReachesVelocityLimit) {
  const double d = 1.0, v = 10.0, a = 2.0, j = 10.0;
  const JerkProfile p = rest_to_rest(d, {v, a, j});
  EXPECT_NEAR(p.duration(), a / j + std::sqrt((a / j) * (a / j) + 4.0 * d / a), 1e-12);  // 1.628 s
  EXPECT_EQ(p.size(), 6u);                                                               // no cruise
  EXPECT_NEAR(p.end().position, d, 1e-12);
  EXPECT_LT(p.at(p.duration() / 2).velocity, v);
}

TEST(RestToRest, VeryShortMoveReachesNeitherLimit) {
  const double d = 0.01, v = 10.0, a = 10.0, j = 10.0;
  const JerkProfile p = rest_to_rest(d, {v, a, j});
  EXPECT_NEAR(p.duration(), 4.0 * std::cbrt(d / (2.0 * j)), 1e-12);
  EXPECT_EQ(p.size(), 4u);
  EXPECT_NEAR(p.end().position, d, 1e-14);
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-14);
}

TEST(RestToRest, NegativeDistanceMirrors) {
  const JerkProfile p = rest_to_rest(-10.0, {1.0, 2.0, 10.0});
  EXPECT_NEAR(p.duration(), 10.7, 1e-12);
  EXPECT_NEAR(p.end().position, -10.0, 1e-12);
  EXPECT_NEAR(p.at(5.0).velocity, -1.0, 1e-12);
}

TEST(RestToRest, ZeroDistanceIsEmpty) {
  const JerkProfile p = rest_to_rest(0.0, {1.0, 2.0, 10.0});
  EXPECT_EQ(p.duration(), 0.0);
  EXPECT_EQ(p.size(), 0u);
}

TEST(BrakeToRest, FromCruiseMirrorsTheAccelerationPhase) {
  const JerkProfile p = brake_to_rest({0.0, 1.0, 0.0}, {1.0, 2.0, 10.0});
  EXPECT_NEAR(p.duration(), 1.0 / 2.0 + 2.0 / 10.0, 1e-12);
  EXPECT_NEAR(p.end().position, 0.35, 1e-12);  // mean velocity 1/2 over 0.7 s
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-12);
  EXPECT_NEAR(p.end().acceleration, 0.0, 1e-12);
}

TEST(BrakeToRest, WhileStillAcceleratingOvershootsThenStops) {
  // Moving at 0.5 with +1 acceleration: the acceleration must first be ramped down.
  const AxisLimits lim{1.0, 2.0, 10.0};
  const JerkProfile p = brake_to_rest({0.0, 0.5, 1.0}, lim);
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-12);
  EXPECT_NEAR(p.end().acceleration, 0.0, 1e-12);
  double v_max = 0.0;
  for (double t = 0.0; t <= p.duration(); t += 1e-4) {
    const MotionState s = p.at(t);
    v_max = std::max(v_max, s.velocity);
    EXPECT_LE(std::abs(s.acceleration), lim.acceleration + 1e-12);
    EXPECT_GE(s.velocity, -1e-12);  // never reverses
  }
  EXPECT_NEAR(v_max, 0.5 + 1.0 / (2.0 * 10.0), 1e-6);  // v + a^2/2j: the least possible peak
}

TEST(BrakeToRest, OnlyAccelerationLeftRampsItToZero) {
  // v + a|a|/2j == 0: a single jerk segment lands exactly at rest.
  const JerkProfile p = brake_to_rest({0.0, 0.05, -1.0}, {1.0, 2.0, 10.0});
  EXPECT_EQ(p.size(), 1u);
  EXPECT_NEAR(p.duration(), 0.1, 1e-12);
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-12);
}

TEST(BrakeToRest, AccelerationAboveTheLimitIsBroughtBackFirst) {
  const AxisLimits lim{1.0, 2.0, 10.0};
  const JerkProfile p = brake_to_rest({0.0, -2.0, 3.0}, lim);  // decelerating at 3 > a_max
  EXPECT_NEAR(p.end().velocity, 0.0, 1e-12);
  EXPECT_NEAR(p.end().acceleration, 0.0, 1e-12);
  EXPECT_NEAR(p.at(0.1).acceleration, 2.0, 1e-12);  // 3 - 10 * 0.1: back at the limit
}

TEST(BrakeToRest, AtRestIsEmpty) {
  const JerkProfile p = brake_to_rest({4.0, 0.0, 0.0}, {1.0, 2.0, 10.0});
  EXPECT_EQ(p.duration(), 0.0);
  EXPECT_EQ(p.end().position, 4.0);
}

}  // namespace
}  // namespace cellctl::planner

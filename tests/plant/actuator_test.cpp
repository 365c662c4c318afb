#include "plant/actuator.hpp"

#include <gtest/gtest.h>

namespace cellctl::plant {
namespace {

using namespace std::chrono_literals;

void run(Actuator& a, link::Duration total, link::Duration dt = 1ms) {
  for (link::Duration t{}; t < total; t += dt) a.step(dt);
}

TEST(Actuator, SoftMoveArrivesExactlyAndStops) {
  Actuator a({.stroke_mm = 200, .max_speed_mm_s = 20, .ramp_mm_s2 = 40, .min_speed_mm_s = 0.8});
  a.move_to(50.0, 20.0, true);
  run(a, 100ms);
  EXPECT_GT(a.velocity_mm_s(), 0.0);
  EXPECT_LT(a.velocity_mm_s(), 20.0) << "still on the start ramp";
  run(a, 5s);
  EXPECT_DOUBLE_EQ(a.position_mm(), 50.0);
  EXPECT_FALSE(a.moving());
  EXPECT_FALSE(a.active());
}

TEST(Actuator, FastStartIsAtFullSpeedAtOnce) {
  Actuator a({});
  a.move_to(100.0, 10.0, false);
  a.step(1ms);
  EXPECT_DOUBLE_EQ(a.velocity_mm_s(), 10.0);
}

TEST(Actuator, BelowTheThresholdNothingMoves) {
  Actuator a({.min_speed_mm_s = 1.0});
  a.move_to(100.0, 0.5, true);
  run(a, 2s);
  EXPECT_DOUBLE_EQ(a.position_mm(), 0.0);
  EXPECT_TRUE(a.stalled());
  a.set_speed(5.0);
  run(a, 1s);
  EXPECT_GT(a.position_mm(), 0.0) << "a speed change during the command gets it going";
}

TEST(Actuator, SoftStopRampsDownFastStopIsImmediate) {
  Actuator a({.max_speed_mm_s = 20, .ramp_mm_s2 = 40});
  a.move_to(200.0, 20.0, false);
  run(a, 1s);
  a.stop(true);
  a.step(100ms);
  EXPECT_NEAR(a.velocity_mm_s(), 16.0, 1e-9);
  run(a, 1s);
  EXPECT_FALSE(a.moving());
  a.move_to(200.0, 20.0, false);
  a.step(1ms);
  a.stop(false);
  EXPECT_FALSE(a.moving());
  EXPECT_FALSE(a.active());
}

TEST(Actuator, ScaleErrorSeparatesIndicatedFromTrue) {
  Actuator a({.scale_error = 0.01});
  a.move_to(100.0, 20.0, false);
  run(a, 10s);
  EXPECT_DOUBLE_EQ(a.position_mm(), 100.0);
  EXPECT_NEAR(a.true_position_mm(), 100.0 / 1.01, 1e-9);
}

TEST(Actuator, StaysInsideTheStroke) {
  Actuator a({.stroke_mm = 100});
  a.move_to(150.0, 20.0, false);
  run(a, 10s);
  EXPECT_DOUBLE_EQ(a.position_mm(), 100.0);
  EXPECT_TRUE(a.at_out_limit());
}

TEST(Actuator, BlockedActuatorDoesNotMove) {
  Actuator a({});
  a.set_blocked(true);
  a.move_to(50.0, 20.0, false);
  run(a, 1s);
  EXPECT_DOUBLE_EQ(a.position_mm(), 0.0);
  EXPECT_TRUE(a.stalled());
}

}  // namespace
}  // namespace cellctl::plant

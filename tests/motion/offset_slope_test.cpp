// The drift of the SCU's reading against the encoder's, as the move executor learns it in motion:
// the slope of (SCU − encoder) over the position, from SCU readings quantised to its 0.1 mm edges and
// delayed on the line. The delay must not bend the slope, at a steady speed or a changing one; the
// standard error must say how well the slope is known.

#include "motion/offset_slope.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cellctl::motion {
namespace {

// An SCU that reads `scale_error` long, with 0.1 mm edges, its reading `delay_s` old at `speed`.
double scu_reading(double true_mm, double scale_error, double delay_s, double speed) {
  return std::round((true_mm - speed * delay_s) * (1.0 + scale_error) * 10.0) / 10.0;
}

TEST(OffsetSlope, ASteadyMoveGivesTheScaleErrorWhateverTheReplyDelay) {
  for (const double delay_s : {0.0, 0.011, 0.05}) {
    OffsetSlope fit;
    const double speed = 10.0;
    // One reading per 100 ms keep-alive from 5 to 65 mm.
    for (double x = 5.0; x <= 65.0; x += speed * 0.1)
      fit.add(x, speed, scu_reading(x, 0.002, delay_s, speed) - x);
    EXPECT_EQ(fit.count(), 61u);
    EXPECT_NEAR(fit.span_mm(), 60.0, 1e-9);
    EXPECT_NEAR(fit.slope(), 0.002, 3.0 * fit.slope_error()) << "delay " << delay_s;
    // The 0.1 mm edges leave the slope known to better than 0.0005 over 60 mm.
    EXPECT_LT(fit.slope_error(), 5e-4);
    EXPECT_GT(fit.slope_error(), 0.0);
  }
}

// The speed modulation changes the speed in steps during the move (here 10, 10.6, then 10.3 mm/s):
// with the delay's share not taken out, the offset jumps at each step and a sensor without any scale
// error looks like one with a drift.
TEST(OffsetSlope, SpeedStepsDuringTheMoveAreNotTakenForADrift) {
  for (const double scale_error : {0.0, 0.002}) {
    OffsetSlope fit;
    const double delay_s = 0.05;
    double x = 5.0;
    for (int k = 0; k < 80; ++k) {
      const double speed = k < 30 ? 10.0 : k < 50 ? 10.6 : 10.3;
      fit.add(x, speed, scu_reading(x, scale_error, delay_s, speed) - x);
      x += speed * 0.1;
    }
    EXPECT_NEAR(fit.slope(), scale_error, 3.0 * fit.slope_error()) << "scale error " << scale_error;
    EXPECT_LT(fit.slope_error(), 5e-4);
  }
}

// A speed that creeps up in step with the position (10 to 12 mm/s over the move) cannot be told
// from a drift: the slope's error says so, and a sensor without scale error is not found to have one.
TEST(OffsetSlope, ASpeedThatCreepsWithThePositionLeavesTheDriftUnproven) {
  OffsetSlope fit;
  double x = 5.0;
  for (int k = 0; k < 80; ++k) {
    const double speed = 10.0 + 2.0 * k / 79.0;
    fit.add(x, speed, scu_reading(x, 0.0, 0.011, speed) - x);
    x += speed * 0.1;
  }
  EXPECT_LT(std::abs(fit.slope()), 3.0 * fit.slope_error());
}

// Speed and position moving together (a ramp sampled at one place per speed) cannot be told apart:
// the slope is then said to be unknown, not made up.
TEST(OffsetSlope, PositionAndSpeedInLockstepLeaveTheSlopeUnknown) {
  OffsetSlope fit;
  for (int k = 0; k < 20; ++k) fit.add(10.0 + k, 2.0 + 0.5 * k, 0.01 * (k % 3));
  EXPECT_GT(fit.slope_error(), 1.0);
}

TEST(OffsetSlope, NoSlopeIsClaimedBeforeThereIsALine) {
  OffsetSlope fit;
  EXPECT_EQ(fit.slope(), 0.0);
  EXPECT_TRUE(std::isinf(fit.slope_error()));
  fit.add(1.0, 5.0, 0.1);
  fit.add(1.0, 5.0, 0.2);  // one position twice: no line yet
  EXPECT_EQ(fit.slope(), 0.0);
  EXPECT_TRUE(std::isinf(fit.slope_error()));
  fit.add(2.0, 5.0, 0.3);
  EXPECT_TRUE(std::isfinite(fit.slope_error()));
  fit.reset();
  EXPECT_EQ(fit.count(), 0u);
  EXPECT_EQ(fit.span_mm(), 0.0);
}

TEST(OffsetSlope, AnExactLineHasNoError) {
  OffsetSlope fit;
  for (int k = 0; k < 10; ++k) fit.add(100.0 + k, 8.0, 0.5 - 0.01 * k);
  EXPECT_NEAR(fit.slope(), -0.01, 1e-12);
  EXPECT_NEAR(fit.slope_error(), 0.0, 1e-9);
}

}  // namespace
}  // namespace cellctl::motion

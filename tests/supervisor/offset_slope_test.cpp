// The drift of the SCU's reading against the encoder's, as the move executor learns it in motion:
// the slope of (SCU − encoder) over the position, from SCU readings quantised to its 0.1 mm edges and
// delayed on the line. The delay at a steady speed must not bend the slope; the standard error must
// say how well the slope is known.

#include "supervisor/offset_slope.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cellctl::supervisor {
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
    for (double x = 5.0; x <= 65.0; x += speed * 0.1) fit.add(x, scu_reading(x, 0.002, delay_s, speed) - x);
    EXPECT_EQ(fit.count(), 61u);
    EXPECT_NEAR(fit.span_mm(), 60.0, 1e-9);
    EXPECT_NEAR(fit.slope(), 0.002, 3.0 * fit.slope_error()) << "delay " << delay_s;
    // The 0.1 mm edges leave the slope known to better than 0.0005 over 60 mm.
    EXPECT_LT(fit.slope_error(), 5e-4);
    EXPECT_GT(fit.slope_error(), 0.0);
  }
}

TEST(OffsetSlope, NoSlopeIsClaimedBeforeThereIsALine) {
  OffsetSlope fit;
  EXPECT_EQ(fit.slope(), 0.0);
  EXPECT_TRUE(std::isinf(fit.slope_error()));
  fit.add(1.0, 0.1);
  fit.add(1.0, 0.2);  // one position twice: no line yet
  EXPECT_EQ(fit.slope(), 0.0);
  EXPECT_TRUE(std::isinf(fit.slope_error()));
  fit.add(2.0, 0.3);
  EXPECT_TRUE(std::isfinite(fit.slope_error()));
  fit.reset();
  EXPECT_EQ(fit.count(), 0u);
  EXPECT_EQ(fit.span_mm(), 0.0);
}

TEST(OffsetSlope, AnExactLineHasNoError) {
  OffsetSlope fit;
  for (int k = 0; k < 10; ++k) fit.add(100.0 + k, 0.5 - 0.01 * k);
  EXPECT_NEAR(fit.slope(), -0.01, 1e-12);
  EXPECT_NEAR(fit.slope_error(), 0.0, 1e-9);
}

}  // namespace
}  // namespace cellctl::supervisor

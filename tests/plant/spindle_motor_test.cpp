#include "plant/spindle_motor.hpp"

#include <gtest/gtest.h>

namespace cellctl::plant {
namespace {

using namespace std::chrono_literals;

TEST(SpindleMotor, RunsUpAndDownOnItsRamps) {
  SpindleMotor m({.ramp_up_hz_s = 400, .ramp_down_hz_s = 200});
  m.run(400, true);
  m.step(500ms);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), 200.0);
  m.step(1s);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), 400.0);
  m.stop();
  m.step(1s);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), 200.0);
  m.step(1s);
  EXPECT_TRUE(m.at_rest());
}

TEST(SpindleMotor, DirectionIsTheSign) {
  SpindleMotor m({.ramp_up_hz_s = 1000, .ramp_down_hz_s = 1000});
  m.run(300, false);
  m.step(1s);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), -300.0);
  m.run(300, true);  // reversal runs down through zero on the down ramp
  m.step(300ms);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), 0.0);
  m.step(300ms);
  EXPECT_DOUBLE_EQ(m.frequency_hz(), 300.0);
}

}  // namespace
}  // namespace cellctl::plant

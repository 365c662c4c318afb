#pragma once
// The physics of the spindle as its converter sees it: the output frequency runs up and down on
// ramps toward the set frequency, in the chosen direction; at 0 Hz the motor stands still.

#include "link/clock.hpp"

namespace cellctl::plant {

struct SpindleMotorParams {
  double ramp_up_hz_s = 400.0;
  double ramp_down_hz_s = 400.0;
};

class SpindleMotor {
 public:
  explicit SpindleMotor(const SpindleMotorParams& params) noexcept : params_(params) {}

  // Runs toward hz (≥ 0) clockwise or counter-clockwise. A change of direction runs down through 0.
  void run(double hz, bool clockwise) noexcept;
  // Runs down to rest on the ramp.
  void stop() noexcept { target_hz_ = 0.0; }
  void step(link::Duration dt) noexcept;

  // Signed actual frequency: positive clockwise.
  [[nodiscard]] double frequency_hz() const noexcept { return frequency_; }
  [[nodiscard]] double target_hz() const noexcept { return target_hz_; }
  [[nodiscard]] bool at_rest() const noexcept { return frequency_ == 0.0; }
  [[nodiscard]] const SpindleMotorParams& params() const noexcept { return params_; }

 private:
  SpindleMotorParams params_;
  double target_hz_ = 0.0;  // signed
  double frequency_ = 0.0;  // signed
};

}  // namespace cellctl::plant

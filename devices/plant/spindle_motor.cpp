#include "plant/spindle_motor.hpp"

#include <cmath>

namespace cellctl::plant {

void SpindleMotor::run(double hz, bool clockwise) noexcept {
  target_hz_ = clockwise ? std::abs(hz) : -std::abs(hz);
}

void SpindleMotor::step(link::Duration dt_ns) noexcept {
  const double dt = link::to_seconds(dt_ns);
  if (dt <= 0.0 || frequency_ == target_hz_) return;
  // Speeding up means moving away from 0 in the target's direction; anything else is running down.
  const bool speeding_up = std::abs(target_hz_) > std::abs(frequency_) &&
                           (frequency_ == 0.0 || (frequency_ > 0) == (target_hz_ > 0));
  const double rate = speeding_up ? params_.ramp_up_hz_s : params_.ramp_down_hz_s;
  const double max_step = rate * dt;
  const double diff = target_hz_ - frequency_;
  frequency_ = std::abs(diff) <= max_step ? target_hz_ : frequency_ + std::copysign(max_step, diff);
}

}  // namespace cellctl::plant

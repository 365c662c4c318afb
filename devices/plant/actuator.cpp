#include "plant/actuator.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::plant {

Actuator::Actuator(const ActuatorParams& params) noexcept
    : params_(params), position_(std::clamp(params.start_position_mm, 0.0, params.stroke_mm)) {}

void Actuator::move_to(double target_mm, double speed_mm_s, bool soft) noexcept {
  target_ = std::clamp(target_mm, 0.0, params_.stroke_mm);
  speed_ = std::clamp(speed_mm_s, 0.0, params_.max_speed_mm_s);
  soft_ = soft;
  active_ = true;
  stopping_ = false;
  if (!soft_ && can_move()) velocity_ = std::copysign(speed_, target_ - position_);
}

void Actuator::set_speed(double speed_mm_s) noexcept {
  speed_ = std::clamp(speed_mm_s, 0.0, params_.max_speed_mm_s);
}

void Actuator::stop(bool soft) noexcept {
  if (!soft || params_.ramp_mm_s2 <= 0.0) {
    velocity_ = 0.0;
    active_ = false;
    stopping_ = false;
    return;
  }
  stopping_ = active_ || velocity_ != 0.0;
  active_ = stopping_;
}

void Actuator::step(link::Duration dt_ns) noexcept {
  const double dt = link::to_seconds(dt_ns);
  if (dt <= 0.0 || !active_) return;
  if (blocked_) {
    velocity_ = 0.0;
    return;
  }
  const double to_go = target_ - position_;
  const double dir = to_go >= 0.0 ? 1.0 : -1.0;
  const double a = params_.ramp_mm_s2;
  double v = velocity_;

  if (stopping_) {
    const double dv = a * dt;  // only soft stops get here; fast stops zero the speed at once
    v = std::abs(v) <= dv ? 0.0 : v - std::copysign(dv, v);
  } else if (!can_move()) {
    v = 0.0;  // stalled: below the threshold the motor does not turn at all
  } else if (!soft_) {
    v = dir * speed_;
  } else {
    // Cruise at speed_, but slow down so as to arrive at the target on the ramp.
    const double brake_speed = std::sqrt(2.0 * a * std::abs(to_go));
    const double wanted = dir * std::min(speed_, std::max(brake_speed, params_.min_speed_mm_s));
    const double dv = a * dt;
    v = std::abs(wanted - v) <= dv ? wanted : v + std::copysign(dv, wanted - v);
  }

  double next = position_ + v * dt;
  const bool passes_target = !stopping_ && ((dir > 0.0 && next >= target_) || (dir < 0.0 && next <= target_));
  if (passes_target) {
    next = target_;
    v = 0.0;
  }
  next = std::clamp(next, 0.0, params_.stroke_mm);
  if (next == 0.0 || next == params_.stroke_mm) {
    if ((v < 0.0 && next == 0.0) || (v > 0.0 && next == params_.stroke_mm)) v = 0.0;  // end stop
  }
  position_ = next;
  velocity_ = v;
  if ((passes_target || stopping_) && v == 0.0) {
    active_ = false;
    stopping_ = false;
  }
}

}  // namespace cellctl::plant

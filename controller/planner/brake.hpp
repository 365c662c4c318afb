#pragma once
// The brake pre-profile: from a start state beyond an axis's limits (or one that will cross them
// whatever the jerk does next, e.g. at max_velocity still accelerating) to the first state from
// which the limits can be kept. Braking means full jerk towards the limit's side, the acceleration
// held at its bound, until the velocity is back at its bound. The overshoot during the brake is
// unavoidable; every later segment keeps the limits.

#include "planner/axis_limits.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// True when (v, a) is inside the limits and the velocity limit can still be kept: ramping the
// acceleration to zero at full jerk does not cross max_velocity (a > 0) or min_velocity (a < 0).
[[nodiscard]] bool is_safe(double v, double a, const AxisLimits& limits) noexcept;

// Empty (duration 0) when the start is safe. Otherwise ends in a safe state, except for limits so
// narrow that none exists (max_velocity - min_velocity below what one acceleration ramp changes
// the velocity by): check is_safe on the end.
[[nodiscard]] JerkProfile brake_profile(const MotionState& start, const AxisLimits& limits) noexcept;

}  // namespace cellctl::planner

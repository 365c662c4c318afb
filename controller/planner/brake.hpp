#pragma once
// The brake pre-profile: from a start state beyond an axis's limits (its acceleration beyond a
// bound, or its velocity beyond one or bound to cross one whatever the jerk does next, e.g. at
// max_velocity still accelerating) into the safe states, those from which the limits can be kept,
// by the shortest jerk-limited path. Every start has one (the limits have min < 0 < max), so no
// start is refused. The overshoot during the brake is unavoidable; every later segment keeps the
// limits.
//
// The path (why it is the shortest): an acceleration beyond its bound comes back at full jerk
// first. Then the velocity is brought back from the side it is beyond (or bound to cross) at full
// jerk away from it: that jerk keeps v + a^2 / 2J (the velocity once the acceleration is ramped
// out) unchanged while the acceleration turns, and then brings the velocity back fastest. The
// ramp is ended early, before it would leave more acceleration than the velocity range can ramp
// out: where ramping it out would end exactly at the opposite limit (the path then follows that
// boundary at full opposite jerk until the velocity is back within its limit), or at the
// acceleration bound (held there). A start beyond one velocity limit and bound to cross the other
// is braked against the acceleration that will cross it: the velocity it is beyond is regained on
// the way. The independent check is tests/planner/brake_oracle.hpp (the earliest entry into the
// safe states, found without these cases).

#include "planner/axis_limits.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// True when (v, a) is a safe state (up to rounding): inside the limits, and ramping the
// acceleration to zero at full jerk crosses neither max_velocity (a > 0) nor min_velocity (a < 0).
[[nodiscard]] bool is_safe(double v, double a, const AxisLimits& limits) noexcept;

// Made in `out` (an axis's own brake, without a copy of it per plan): empty (duration 0) when the
// start is safe; otherwise it ends in a safe state (up to rounding).
void brake_profile(const MotionState& start, const AxisLimits& limits, JerkProfile& out) noexcept;

}  // namespace cellctl::planner

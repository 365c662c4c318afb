#pragma once
// The two shapes the planner is made of, for one axis:
// - rest_to_rest: the time-optimal 7-segment S-curve (jerk +j, 0, -j, cruise, -j, 0, +j) covering a
//   distance from rest to rest, including the short moves where the maximum acceleration or the
//   maximum velocity is never reached, and the zero move;
// - brake_to_rest: the time-optimal jerk-limited stop from any (velocity, acceleration).

#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// Strictly positive, finite limits (the planner validates them before building shapes).
struct AxisLimits {
  double velocity = 0.0;
  double acceleration = 0.0;
  double jerk = 0.0;
};

// Starts at position 0 at rest and ends at `distance` (signed) at rest.
[[nodiscard]] JerkProfile rest_to_rest(double distance, const AxisLimits& limits) noexcept;

// Starts at `start` and ends with zero velocity and zero acceleration as early as the acceleration
// and jerk limits allow. If the start acceleration exceeds the limit, it is first brought back to
// it at full jerk (the limits may have been lowered mid-motion).
[[nodiscard]] JerkProfile brake_to_rest(const MotionState& start, const AxisLimits& limits) noexcept;

}  // namespace cellctl::planner

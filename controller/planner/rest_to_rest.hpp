#pragma once
// The shortest duration from rest to rest over a distance, in closed form: the common case (every
// recipe move from a standstill) needs no root search. Accelerating uses the limits of the
// direction of travel, braking the opposite acceleration bound (max_acceleration/min_acceleration
// may differ).

#include "planner/axis_limits.hpp"

namespace cellctl::planner {

// distance: signed; limits: finite and of the right signs. Returns 0 for a zero distance.
[[nodiscard]] double rest_to_rest_time(double distance, const AxisLimits& limits) noexcept;

}  // namespace cellctl::planner

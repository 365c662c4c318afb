#pragma once
// Axis i's limits in the planner's input for a move at `speed_mm_s`: the move's speed (never over the
// axis's own), the axis's acceleration and jerk from the cell's config. What a MoveExecutor plans a
// move by, and what a program's planned time is made of (planned_time.hpp).

#include <algorithm>
#include <cstddef>

#include "config/cell_core.hpp"
#include "planner/input.hpp"

namespace cellctl::motion {

inline void limit_axis(const config::CellCore& cell, double speed_mm_s, std::size_t i,
                       planner::Input<6>& in) noexcept {
  const auto k = static_cast<Eigen::Index>(i);
  in.max_velocity[k] = std::min(speed_mm_s, cell.axes[i].max_speed_mm_s);
  in.max_acceleration[k] = cell.axes[i].max_accel_mm_s2;
  in.max_jerk[k] = cell.axes[i].max_jerk_mm_s3;
}

}  // namespace cellctl::motion

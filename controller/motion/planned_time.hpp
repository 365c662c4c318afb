#pragma once
// A program's time as the supervisor sequences it, planned without running it: each move the
// planner's jerk-limited profile from where its axes stand (the same planner and the same limits a
// MoveExecutor plans the move by: the move's speed, each axis's velocity, acceleration and jerk limits
// from the cell's config); each dwell its seconds; each spindle start or stop its converter's ramp
// from the speed before to the speed asked for, when the ramps are known. What only the run can tell
// is counted apart (recipe::PlannedTime::not_counted).
//
// What it leaves out, and the run has: the devices' start-up, the line's telegrams before an axis
// moves, the SCU's own trapezoid (its ramp, no jerk limit) under the planned profile, the settle
// before a move is judged (it overlaps the profile's slow end), an encoder's corrections, the
// converter's speed as polled rather than as it turns. Pure: no clock, no I/O.

#include <optional>
#include <span>

#include "config/cell_core.hpp"
#include "recipe/planned_time.hpp"
#include "recipe/program.hpp"

namespace cellctl::motion {

// The spindle converter's ramps (its own parameters: an emulator's, or the converter's as set up).
struct SpindleRamps {
  double up_hz_s = 0.0;
  double down_hz_s = 0.0;
};

[[nodiscard]] recipe::PlannedTime planned_time(const config::CellCore& cell, const recipe::Program& program,
                                               std::span<const std::optional<double>> start_mm,
                                               const std::optional<SpindleRamps>& spindle);

}  // namespace cellctl::motion

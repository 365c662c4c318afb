#pragma once
// A program's planned time, before it runs: what the page's Start list shows beside each recipe. It is
// made where the planner is seen (motion/planned_time.hpp) and handed to who may not see it (the
// page) as a ProgramTimer by the command line, which sees both.

#include <cstddef>
#include <functional>
#include <optional>
#include <span>

#include "recipe/program.hpp"

namespace cellctl::recipe {

struct PlannedTime {
  double seconds = 0.0;
  // Steps whose time only the run can tell, not in `seconds`: a wait on the cell, a homing, a
  // Teach-In, a move of an axis whose start is not known, a spindle whose ramps are not known.
  std::size_t not_counted = 0;
};

// The planned time of a program that starts with each axis where `start_mm` says (by the cell's axis
// index; nullopt: not known) and the spindle at rest.
using ProgramTimer =
    std::function<PlannedTime(const Program& program, std::span<const std::optional<double>> start_mm)>;

}  // namespace cellctl::recipe

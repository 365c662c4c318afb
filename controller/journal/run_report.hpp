#pragma once
// What `cellctl report RUN_DIR` prints and exports: a run an engineer reads — where it came from,
// each step with its planned and actual time, the faults and commands, the largest following error
// per axis, the loop's timing, the spindle — and its samples as CSV for a spreadsheet or a scope.

#include <ostream>
#include <string>

#include "journal/run_record.hpp"

namespace cellctl::journal {

[[nodiscard]] std::string report_text(const RunRecord& run);

// One row per sample: t_s, step, per axis <name>_planned_mm, <name>_scu_mm, then encoder_mm
// (of the measured axis), spindle_set_hz, spindle_hz; the header names the columns.
void write_csv(const RunRecord& run, std::ostream& out);

struct MaxFollowingError {
  double mm = 0.0;  // signed, the largest in magnitude
  double t = 0.0;
  int step = 0;
};
// Per axis, during moves (plot_model.hpp's following_error).
[[nodiscard]] std::vector<MaxFollowingError> max_following_errors(const RunRecord& run);

// The step running at time t (1-based), 0 before the first.
[[nodiscard]] int step_at(const RunRecord& run, double t);

}  // namespace cellctl::journal

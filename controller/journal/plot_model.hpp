#pragma once
// What the plots show, computed once from one run record (or two, overlaid, for `cellctl compare`)
// and drawn twice: as plot.svg (static, for any viewer and for print) and as plot.html (zoom and
// values on hover). Panels: axis positions (planned, SCU, encoder), following error (planned −
// measured, during moves), spindle (set, actual), each with its axis titles and units; every step's
// boundary with its label; marks for faults, injected faults, operator commands and resets; the
// stretches the cell was held. The step labels are laid out here, once, for both drawings: each in a
// lane of its own above the panels where it overlaps no other, drawn whole at a fixed width per
// character (SVG textLength, the canvas's maxWidth), so neither drawing cuts or skips one.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "journal/run_record.hpp"
#include "schema/plot_data.hpp"

namespace cellctl::journal {

using schema::kLabelCharPx;
using schema::kLabelFontPx;
using schema::kLabelGapPx;
using schema::kLaneHeightPx;
using schema::kMarkNumberPx;
using schema::kPlotAreaPx;
using schema::kTimeTicks;
using schema::PlotHold;
using schema::PlotMark;
using schema::PlotModel;
using schema::PlotPanel;
using schema::PlotSeries;
using schema::PlotStep;

// One run, or runs overlaid on their own start times (the first one's steps are drawn).
[[nodiscard]] PlotModel plot_model(const std::vector<const RunRecord*>& runs);

// planned − measured of an axis (encoder where it measures the axis, else the SCU) at each sample,
// NaN outside move steps (before the first move the plan is not the axis's).
[[nodiscard]] std::vector<double> following_error(const RunRecord& run, std::size_t axis);

// "drill hole 1 2/2 › peck in (line 27)" → "peck in".
[[nodiscard]] std::string short_step_name(std::string_view label);

// The width a label is drawn at: kLabelCharPx per character (UTF-8 aware).
[[nodiscard]] double label_width_px(std::string_view label);

// The note a run journals for a typed reset or clear it did not take as a command (faults reset while
// held, refused, not possible in the state): "reset", "clear", or "" for any other note.
[[nodiscard]] std::string_view reset_of_note(std::string_view note);

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

}  // namespace cellctl::journal

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

namespace cellctl::journal {

struct PlotSeries {
  std::string name;    // "x planned", "B: z SCU"
  std::string colour;  // CSS colour
  std::string dash;    // SVG stroke-dasharray, "" for solid
  std::vector<double> t;
  std::vector<double> v;  // NaN: no value (a gap)
};

struct PlotPanel {
  std::string title;       // "Axis positions"
  std::string unit;        // "mm"
  std::string value_axis;  // the value axis's title with its unit: "position [mm]"
  std::vector<PlotSeries> series;
};

// The geometry the step labels are laid out for: a plot area this wide showing the whole run (plot.svg's;
// plot.html's is at least as wide, and zooming in only spreads the labels apart).
inline constexpr double kPlotAreaPx = 880.0;
inline constexpr double kLabelFontPx = 10.0;
inline constexpr double kLabelCharPx = 6.0;  // a label is drawn this wide per character, whatever the font
inline constexpr double kLabelGapPx = 6.0;   // between two labels in one lane
inline constexpr double kLaneHeightPx = 13.0;
inline constexpr double kMarkNumberPx = 12.0;  // a mark's number: its width and its row's height
inline constexpr int kTimeTicks = 14;          // about as many ticks on the time axis of the whole run

struct PlotStep {
  double t = 0.0;
  int step = 0;
  std::string name;   // short: "peck in"
  std::string full;   // the run's label
  std::string label;  // as drawn, whole: "7 peck in"
  int lane = 0;       // 0: the lane nearest the panels
  // The label's box in px from the plot area's left edge, the whole run in view: right of the step's
  // boundary, or left of it near the end of the run.
  double box_left = 0.0;
  double box_right = 0.0;
};

struct PlotHold {
  double from = 0.0;
  double to = 0.0;
};

struct PlotMark {
  double t = 0.0;
  std::string kind;  // fault, injected fault, fault cleared, command, reset
  std::string text;
  std::string colour;
  int level = 0;  // its number's row above the step labels: marks closer than a number's width stack
};

struct PlotModel {
  std::string title;                  // recipe, outcome, duration
  std::vector<std::string> subtitle;  // one per run: mode, host, cellctl version, start
  std::vector<PlotPanel> panels;
  std::vector<PlotStep> steps;  // of the first run
  int lanes = 1;                // the step labels' lanes
  std::vector<PlotMark> marks;  // of every run (prefixed "A:"/"B:" when overlaid)
  int mark_levels = 0;          // rows of mark numbers
  std::vector<PlotHold> holds;  // of the first run
  double t_lo = 0.0;            // the whole run on the time scale's round ticks
  double t_hi = 1.0;
};

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

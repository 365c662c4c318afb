#pragma once
// What the plots show, computed once from one run record (or two, overlaid, for `cellctl compare`)
// and drawn twice: as plot.svg (static, for any viewer and for print) and as plot.html (zoom and
// values on hover). Panels: axis positions (planned, SCU, encoder), following error (planned −
// measured, during moves), spindle (set, actual); step boundaries with names; marks for faults,
// injected faults and operator commands.

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
  std::string title;  // "Axis positions"
  std::string unit;   // "mm"
  std::vector<PlotSeries> series;
};

struct PlotStep {
  double t = 0.0;
  int step = 0;
  std::string name;  // short: "peck in"
  std::string full;  // the run's label
};

struct PlotMark {
  double t = 0.0;
  std::string kind;  // fault, injected fault, fault cleared, command
  std::string text;
  std::string colour;
};

struct PlotModel {
  std::string title;                  // recipe, outcome, duration
  std::vector<std::string> subtitle;  // one per run: mode, host, cellctl version, start
  std::vector<PlotPanel> panels;
  std::vector<PlotStep> steps;  // of the first run
  std::vector<PlotMark> marks;  // of every run (prefixed "A:"/"B:" when overlaid)
  double t_lo = 0.0;
  double t_hi = 1.0;
};

// One run, or runs overlaid on their own start times (the first one's steps are drawn).
[[nodiscard]] PlotModel plot_model(const std::vector<const RunRecord*>& runs);

// planned − measured of an axis (encoder where it measures the axis, else the SCU) at each sample,
// NaN outside move steps (before the first move the plan is not the axis's).
[[nodiscard]] std::vector<double> following_error(const RunRecord& run, std::size_t axis);

// "drill hole 1 2/2 › peck in (line 27)" → "peck in".
[[nodiscard]] std::string short_step_name(std::string_view label);

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

}  // namespace cellctl::journal

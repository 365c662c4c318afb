#pragma once
// What a run's plots show, laid out once (journal/plot_model.hpp computes it from the run record) and
// drawn twice: plot.svg, and plot.html, which carries it as its data (plot_data_json) for its script.
// The step labels' geometry is fixed here, so that both drawings and the data agree on it.

#include <string>
#include <vector>

namespace cellctl::schema {

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

// The data plot.html's script draws: the model, its numbers rounded to 0.1 ms and 0.0001 of a unit,
// a series' time stamps written once when series share them, "</" escaped so that the data cannot end
// its script element.
[[nodiscard]] std::string plot_data_json(const PlotModel& model);

}  // namespace cellctl::schema

#include "journal/plot_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "journal/plot_scale.hpp"

namespace cellctl::journal {
namespace {

// Per axis; the second run of a comparison in the paler twin of each.
constexpr const char* kAxisColours[2][6] = {
    {"#1f5fa8", "#c0392b", "#2e8b3a", "#7b4fa0", "#8c564b", "#d0508f"},
    {"#7fb2e5", "#eea39a", "#8fd19b", "#c2a5df", "#c9a196", "#f0a8cb"}};
constexpr const char* kSpindleColours[2] = {"#e07b00", "#f5bf73"};
constexpr const char* kEncoderColours[2] = {"#222222", "#9a9a9a"};

std::string prefixed(std::size_t run, std::size_t runs, const std::string& name) {
  return runs > 1 ? fmt::format("{}: {}", run == 0 ? "A" : "B", name) : name;
}

std::string mark_colour(MarkKind k) {
  switch (k) {
    case MarkKind::fault:
      return "#d00000";
    case MarkKind::injected_fault:
      return "#9b00c8";
    case MarkKind::fault_cleared:
      return "#2e8b3a";
    case MarkKind::command:
      return "#0060c0";
    case MarkKind::note:  // a reset's answer: the only notes the plot marks
      return "#b06000";
  }
  return "#666666";
}

bool is_move(const RunRecord& run, const StepRun& s) {
  const auto& steps = run.header().steps;
  if (s.step < 1 || static_cast<std::size_t>(s.step) > steps.size()) return true;
  return steps[static_cast<std::size_t>(s.step - 1)].kind == "move";
}

// A run of more than twice this many samples (2 h 40 min at 20 ms) is drawn in this many buckets:
// each bucket by its lowest and highest value in their order, its first gap and the first gap after
// its last value, so peaks survive and a gap on either side of a short stretch of values stays a
// gap, while plot.svg and plot.html stay small enough to open. The record keeps every sample
// (`cellctl report --csv` exports them).
constexpr std::size_t kMaxBuckets = 4000;

template <class Get>
PlotSeries series(const RunRecord& run, std::string name, std::string colour, std::string dash, Get get) {
  PlotSeries s{std::move(name), std::move(colour), std::move(dash), {}, {}};
  const auto& samples = run.samples();
  const std::size_t n = samples.size();
  const std::size_t per = n <= 2 * kMaxBuckets ? 1 : (n + kMaxBuckets - 1) / kMaxBuckets;
  s.t.reserve(std::min(n, 6 * kMaxBuckets));
  s.v.reserve(std::min(n, 6 * kMaxBuckets));
  for (std::size_t first = 0; first < n; first += per) {
    const std::size_t end = std::min(n, first + per);
    std::size_t lo = n, hi = n, gap = n, gap_after = n;
    for (std::size_t i = first; i < end; ++i) {
      const double v = get(i, samples[i]);
      if (std::isnan(v)) {
        gap = std::min(gap, i);
        gap_after = std::min(gap_after, i);
      } else {
        if (lo == n || v < get(lo, samples[lo])) lo = i;
        if (hi == n || v > get(hi, samples[hi])) hi = i;
        gap_after = n;
      }
    }
    // The run's first and last samples too, so that a curve spans the whole run.
    std::array<std::size_t, 6> keep = {
        lo, hi, gap, gap_after, first == 0 ? std::size_t{0} : n, end == n ? n - 1 : n};
    std::sort(keep.begin(), keep.end());
    for (std::size_t k = 0; k < keep.size(); ++k) {
      if (keep[k] == n || (k > 0 && keep[k] == keep[k - 1])) continue;
      s.t.push_back(samples[keep[k]].t - run.start());
      s.v.push_back(get(keep[k], samples[keep[k]]));
    }
  }
  return s;
}

// Each label in the lowest lane where its box keeps kLabelGapPx from every other; steps are in time
// order, so a lane's last box is the one to clear.
int lay_out_labels(std::vector<PlotStep>& steps, double t_lo, double t_hi) {
  std::vector<double> lane_right;
  for (auto& s : steps) {
    s.label = fmt::format("{} {}", s.step, s.name);
    const double x = (s.t - t_lo) / (t_hi - t_lo) * kPlotAreaPx;
    const double w = std::min(label_width_px(s.label), kPlotAreaPx);
    s.box_left = x + 2.0 + w <= kPlotAreaPx ? x + 2.0 : std::max(0.0, x - 2.0 - w);
    s.box_right = s.box_left + w;
    std::size_t lane = 0;
    while (lane < lane_right.size() && lane_right[lane] + kLabelGapPx > s.box_left) ++lane;
    if (lane == lane_right.size()) lane_right.push_back(0.0);
    lane_right[lane] = s.box_right;
    s.lane = static_cast<int>(lane);
  }
  return std::max<int>(1, static_cast<int>(lane_right.size()));
}

// Stacks the numbers of marks closer than a number's width; returns the rows used.
int stack_marks(std::vector<PlotMark>& marks, double t_lo, double t_hi) {
  int rows = 0;
  double last_x = -1e9;
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const double x = (marks[i].t - t_lo) / (t_hi - t_lo) * kPlotAreaPx;
    marks[i].level = i > 0 && x - last_x < kMarkNumberPx ? marks[i - 1].level + 1 : 0;
    rows = std::max(rows, marks[i].level + 1);
    last_x = x;
  }
  return rows;
}

}  // namespace

double label_width_px(std::string_view label) {
  const auto chars = std::count_if(label.begin(), label.end(),
                                   [](char c) { return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u; });
  return static_cast<double>(chars) * kLabelCharPx;
}

std::string_view reset_of_note(std::string_view note) {
  if (note.starts_with("faults reset in state ") || note.starts_with("reset ")) return "reset";
  if (note.starts_with("clear ")) return "clear";
  return {};
}

std::string short_step_name(std::string_view label) {
  if (const auto arrow = label.rfind("› "); arrow != std::string_view::npos)
    label.remove_prefix(arrow + std::string_view("› ").size());
  if (const auto line = label.rfind(" (line "); line != std::string_view::npos) label = label.substr(0, line);
  return std::string(label);
}

std::vector<double> following_error(const RunRecord& run, std::size_t axis) {
  const auto& samples = run.samples();
  std::vector<double> err(samples.size(), kNoValue);
  const auto measured = run.measured_axis();
  // Samples and steps are both in time order: one pass over each (a long run has many of both).
  std::size_t i = 0;
  for (const auto& step : run.steps()) {
    while (i < samples.size() && samples[i].t < step.start) ++i;
    if (!is_move(run, step)) continue;
    for (std::size_t k = i; k < samples.size() && samples[k].t <= step.end; ++k) {
      const auto& p = samples[k];
      if (axis >= p.planned_mm.size()) continue;
      const double actual = measured == axis ? p.encoder_mm : p.scu_mm[axis];
      err[k] = p.planned_mm[axis] - actual;
    }
  }
  return err;
}

PlotModel plot_model(const std::vector<const RunRecord*>& runs) {
  PlotModel m;
  if (runs.empty()) return m;
  const RunRecord& first = *runs.front();
  m.title = fmt::format("{} — {}", first.recipe_label(), runs.size() > 1 ? "comparison" : first.outcome());
  m.panels = {{"Axis positions", "mm", "position [mm]", {}},
              {"Following error (planned − measured, during moves)", "mm", "following error [mm]", {}},
              {"Spindle frequency", "Hz", "frequency [Hz]", {}}};
  m.t_hi = 0.0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const RunRecord& run = *runs[r];
    const auto& h = run.header();
    m.subtitle.push_back(fmt::format("{}{} after {:.2f} s · {} · host {} · cellctl {} · started {}",
                                     runs.size() > 1 ? (r ? "B: " : "A: ") : "", run.outcome(),
                                     run.duration_s(), h.mode.value_or("mode unknown"), h.host.value_or("?"),
                                     h.cellctl.value_or("?"), h.started_utc.value_or("?")));
    m.t_hi = std::max(m.t_hi, run.duration_s());
    const auto names = run.axis_names();
    const auto measured = run.measured_axis();
    const auto pale = std::min<std::size_t>(r, 1);
    for (std::size_t a = 0; a < names.size(); ++a) {
      const char* colour = kAxisColours[pale][a % 6];
      m.panels[0].series.push_back(series(run, prefixed(r, runs.size(), names[a] + " planned"), colour, "7,4",
                                          [a](std::size_t, const SamplePoint& p) {
                                            return a < p.planned_mm.size() ? p.planned_mm[a] : kNoValue;
                                          }));
      m.panels[0].series.push_back(series(
          run, prefixed(r, runs.size(), names[a] + " SCU"), colour, "",
          [a](std::size_t, const SamplePoint& p) { return a < p.scu_mm.size() ? p.scu_mm[a] : kNoValue; }));
      if (measured == a)
        m.panels[0].series.push_back(series(run, prefixed(r, runs.size(), names[a] + " encoder"),
                                            kEncoderColours[pale], "2,3",
                                            [](std::size_t, const SamplePoint& p) { return p.encoder_mm; }));
      const auto err = following_error(run, a);
      m.panels[1].series.push_back(
          series(run,
                 prefixed(r, runs.size(),
                          fmt::format("{} planned − {}", names[a], measured == a ? "encoder" : "SCU")),
                 colour, "", [&err](std::size_t i, const SamplePoint&) { return err[i]; }));
    }
    m.panels[2].series.push_back(series(run, prefixed(r, runs.size(), "spindle set"), kSpindleColours[pale],
                                        "7,4",
                                        [](std::size_t, const SamplePoint& p) { return p.spindle_set_hz; }));
    m.panels[2].series.push_back(series(run, prefixed(r, runs.size(), "spindle actual"),
                                        kSpindleColours[pale], "",
                                        [](std::size_t, const SamplePoint& p) { return p.spindle_hz; }));
    for (const auto& mark : run.marks()) {
      // Notes are in the report, not on the plot; but a typed reset or clear is an operator's command
      // whose only trace may be the note answering it.
      const auto reset = mark.kind == MarkKind::note ? reset_of_note(mark.text) : std::string_view{};
      if (mark.kind == MarkKind::note && reset.empty()) continue;
      m.marks.push_back({mark.t - run.start(), std::string(reset.empty() ? to_string(mark.kind) : reset),
                         prefixed(r, runs.size(), mark.text), mark_colour(mark.kind), 0});
    }
  }
  for (const auto& s : first.steps())
    m.steps.push_back({s.start - first.start(), s.step, short_step_name(s.label), s.label, {}, 0, 0.0, 0.0});
  for (const auto& h : first.holds()) m.holds.push_back({h.from - first.start(), h.to - first.start()});
  std::stable_sort(m.marks.begin(), m.marks.end(),
                   [](const PlotMark& a, const PlotMark& b) { return a.t < b.t; });
  if (m.t_hi <= m.t_lo) m.t_hi = m.t_lo + 1.0;
  // The span both drawings show the whole run in: to the time scale's round ticks.
  const Scale t = nice_scale(m.t_lo, m.t_hi, kTimeTicks);
  m.t_lo = t.lo;
  m.t_hi = t.hi;
  m.lanes = lay_out_labels(m.steps, m.t_lo, m.t_hi);
  m.mark_levels = stack_marks(m.marks, m.t_lo, m.t_hi);
  return m;
}

}  // namespace cellctl::journal

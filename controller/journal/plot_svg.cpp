#include "journal/plot_svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "journal/plot_model.hpp"
#include "journal/plot_scale.hpp"

namespace cellctl::journal {
namespace {

constexpr double kWidth = 1200, kLeft = 80, kPlotRight = kLeft + kPlotAreaPx, kLegendX = 975;
constexpr double kGap = 44;
constexpr double kTitleRow = 16;  // a panel's title above it (the step labels above the first one's)
constexpr double kPanelHeights[] = {300, 150, 190};

std::string xml(std::string_view s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

struct Frame {
  double top, height;
  Scale t, y;
  [[nodiscard]] double x_of(double t_s) const {
    return kLeft + (t_s - t.lo) / (t.hi - t.lo) * (kPlotRight - kLeft);
  }
  [[nodiscard]] double y_of(double v) const { return top + height - (v - y.lo) / (y.hi - y.lo) * height; }
};

Scale value_scale(const PlotPanel& p) {
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (const auto& s : p.series)
    for (const double v : s.v)
      if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo > hi) lo = -1, hi = 1;        // nothing to show (no moves): a symmetric empty scale
  if (lo == 0.0 && hi == 0.0) hi = 1;  // all zero (a spindle never run): no negative half

  return nice_scale(lo, hi, 6);
}

// Tick labels carry their scale's name (data-scale="y0", "t0"), so a test can check each scale.
std::string axes(const Frame& f, const PlotPanel& p, std::size_t index) {
  std::string s = fmt::format(
      R"(<text x="{}" y="{}" font-size="14" font-weight="bold" stroke="white" stroke-width="3" paint-order="stroke">{}</text>)",
      kLeft, f.top - 8, xml(p.title));
  for (const double v : f.y.ticks) {
    s += fmt::format(R"(<line x1="{}" y1="{:.1f}" x2="{}" y2="{:.1f}" stroke="{}"/>)", kLeft, f.y_of(v),
                     kPlotRight, f.y_of(v), v == 0.0 ? "#bbb" : "#eee");
    s += fmt::format(
        R"(<text class="tick" data-scale="y{}" x="{}" y="{:.1f}" font-size="11" text-anchor="end">{}</text>)",
        index, kLeft - 5, f.y_of(v) + 4, f.y.label(v));
  }
  for (const double t : f.t.ticks) {
    s += fmt::format(R"(<line x1="{:.1f}" y1="{}" x2="{:.1f}" y2="{}" stroke="#f2f2f2"/>)", f.x_of(t), f.top,
                     f.x_of(t), f.top + f.height);
    s += fmt::format(
        R"(<text class="tick" data-scale="t{}" x="{:.1f}" y="{}" font-size="11" text-anchor="middle">{}</text>)",
        index, f.x_of(t), f.top + f.height + 14, f.t.label(t));
  }
  s += fmt::format(R"(<text class="axis-title" x="{}" y="{}" font-size="11">time [s]</text>)",
                   kPlotRight + 14, f.top + f.height + 14);
  s += fmt::format(
      R"svg(<text class="axis-title" x="{}" y="{}" font-size="12" text-anchor="middle" transform="rotate(-90 {} {})">{}</text>)svg",
      22, f.top + f.height / 2, 22, f.top + f.height / 2, xml(p.value_axis));
  s += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#888"/>)", kLeft, f.top,
                   kPlotRight - kLeft, f.height);
  return s;
}

// A polyline per stretch of values (NaN breaks it).
std::string curve(const Frame& f, const PlotSeries& s) {
  std::string out, pts;
  const auto flush = [&] {
    if (!pts.empty())
      out += fmt::format(R"(<polyline fill="none" stroke="{}" stroke-width="1.4"{} points="{}"/>)", s.colour,
                         s.dash.empty() ? "" : fmt::format(R"( stroke-dasharray="{}")", s.dash), pts);
    pts.clear();
  };
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    if (std::isnan(s.v[i])) {
      flush();
      continue;
    }
    pts += fmt::format("{:.1f},{:.1f} ", f.x_of(s.t[i]), f.y_of(s.v[i]));
  }
  flush();
  return out;
}

std::string legend(const Frame& f, const PlotPanel& p) {
  std::string s;
  double y = f.top + 10;
  for (const auto& series : p.series) {
    s += fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="2"{}/>)", kLegendX, y,
                     kLegendX + 26, y, series.colour,
                     series.dash.empty() ? "" : fmt::format(R"( stroke-dasharray="{}")", series.dash));
    s += fmt::format(R"(<text class="legend" x="{}" y="{}" font-size="11">{}</text>)", kLegendX + 32, y + 4,
                     xml(series.name));
    y += 16;
  }
  return s;
}

// Every step: its boundary through every panel up to its label, the label whole in its lane, the run's
// own label on hover.
std::string steps(const PlotModel& m, const Frame& f0, const Frame& fl) {
  std::string svg;
  for (const auto& st : m.steps) {
    const double x = f0.x_of(st.t);
    const double baseline = f0.top - kTitleRow - 6 - kLaneHeightPx * st.lane;
    svg += fmt::format(
        R"svg(<g class="step" data-step="{}"><title>{}</title><line class="step-mark" x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{}" stroke="#c8c8c8" stroke-width="0.8"/>)svg"
        R"svg(<text class="step-label" x="{:.1f}" y="{:.1f}" font-size="{}" fill="#444" stroke="white" stroke-width="3" paint-order="stroke" textLength="{:.1f}" lengthAdjust="spacingAndGlyphs">{}</text></g>)svg",
        st.step, xml(st.full), x, baseline - kLabelFontPx + 1, x, fl.top + fl.height, kLeft + st.box_left,
        baseline, kLabelFontPx, st.box_right - st.box_left, xml(st.label));
  }
  return svg;
}

std::string holds(const PlotModel& m, const std::vector<Frame>& frames) {
  std::string svg;
  for (const auto& h : m.holds)
    for (const auto& f : frames)
      svg += fmt::format(
          R"(<rect class="hold" x="{:.1f}" y="{}" width="{:.1f}" height="{}" fill="#f2b53a" fill-opacity="0.18"><title>held {:.3f} s – {:.3f} s</title></rect>)",
          f.x_of(h.from), f.top, std::max(1.0, f.x_of(h.to) - f.x_of(h.from)), f.height, h.from, h.to);
  return svg;
}

}  // namespace

std::string render_svg(const std::vector<const RunRecord*>& runs) {
  const PlotModel m = plot_model(runs);
  const Scale t = nice_scale(m.t_lo, m.t_hi, kTimeTicks);
  const double header = 30 + 15.0 * static_cast<double>(m.subtitle.size());
  std::vector<Frame> frames;
  // The marks' numbers above the step labels' lanes, the panels below them.
  const double marks_row = header + kMarkNumberPx * m.mark_levels + 8;
  double top = marks_row + 8 + kLaneHeightPx * m.lanes + kTitleRow + 8;
  for (std::size_t i = 0; i < m.panels.size(); ++i) {
    frames.push_back({top, kPanelHeights[i % 3], t, value_scale(m.panels[i])});
    top += kPanelHeights[i % 3] + kGap;
  }
  const double list_top = top + 10;
  const double height =
      list_top + 20 + 15.0 * static_cast<double>(std::max<std::size_t>(1, m.marks.size() + m.holds.size()));

  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{:.0f}" viewBox="0 0 {} {:.0f}" font-family="sans-serif">)"
      "\n"
      R"(<rect width="100%" height="100%" fill="white"/>)",
      kWidth, height, kWidth, height);
  svg +=
      fmt::format(R"(<text x="{}" y="20" font-size="15" font-weight="bold">{}</text>)", kLeft, xml(m.title));
  for (std::size_t i = 0; i < m.subtitle.size(); ++i)
    svg += fmt::format(R"(<text x="{}" y="{}" font-size="11" fill="#444">{}</text>)", kLeft, 36 + 15 * i,
                       xml(m.subtitle[i]));
  svg += holds(m, frames);
  const Frame& f0 = frames.front();
  const Frame& fl = frames.back();
  // Marks: a line through every panel (under the step labels, which stay readable), numbered above
  // them, listed below.
  for (const auto& mk : m.marks)
    svg += fmt::format(
        R"(<line class="mark-line" x1="{:.1f}" y1="{}" x2="{:.1f}" y2="{}" stroke="{}" stroke-width="1.2" stroke-dasharray="4,2"><title>{}</title></line>)",
        f0.x_of(mk.t), marks_row + 2, f0.x_of(mk.t), fl.top + fl.height, mk.colour, xml(mk.text));
  svg += steps(m, f0, fl);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    svg += axes(frames[i], m.panels[i], i);
    for (const auto& s : m.panels[i].series) svg += curve(frames[i], s);
    svg += legend(frames[i], m.panels[i]);
  }
  for (std::size_t i = 0; i < m.marks.size(); ++i) {
    const auto& mk = m.marks[i];
    const double x = f0.x_of(mk.t);
    const double y = marks_row - kMarkNumberPx * mk.level;
    svg += fmt::format(
        R"(<text x="{:.1f}" y="{}" font-size="11" font-weight="bold" fill="{}" text-anchor="middle">{}</text>)",
        x, y, mk.colour, i + 1);
    svg += fmt::format(
        R"(<text class="mark" x="{}" y="{}" font-size="11" fill="{}">{}  {:8.3f} s  {}: {}</text>)", kLeft,
        list_top + 15 * static_cast<double>(i + 1), mk.colour, i + 1, mk.t, mk.kind, xml(mk.text));
  }
  for (std::size_t i = 0; i < m.holds.size(); ++i)
    svg += fmt::format(
        R"(<text class="mark" x="{}" y="{}" font-size="11" fill="#a06c00">held {:.3f} s – {:.3f} s ({:.3f} s)</text>)",
        kLeft, list_top + 15 * static_cast<double>(m.marks.size() + i + 1), m.holds[i].from, m.holds[i].to,
        m.holds[i].to - m.holds[i].from);
  if (m.marks.empty() && m.holds.empty())
    svg += fmt::format(
        R"(<text x="{}" y="{}" font-size="11" fill="#444">no faults, no operator commands, no holds</text>)",
        kLeft, list_top + 15);
  svg += "</svg>\n";
  return svg;
}

}  // namespace cellctl::journal

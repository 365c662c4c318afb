#include "journal/plot_svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace cellctl::journal {
namespace {

constexpr double kWidth = 1000, kPanel = 260, kLeft = 70, kRight = 20, kTop = 40, kGap = 50;
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

struct Range {
  double lo = std::numeric_limits<double>::max();
  double hi = std::numeric_limits<double>::lowest();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void pad() {
    if (lo > hi) lo = 0, hi = 1;
    if (hi - lo < 1e-9) hi = lo + 1;
    const double p = (hi - lo) * 0.05;
    lo -= p, hi += p;
  }
};

class Panel {
 public:
  Panel(double top, Range t, Range y, std::string title, std::string unit)
      : top_(top), t_(t), y_(y), title_(std::move(title)), unit_(std::move(unit)) {}

  [[nodiscard]] double x(double t) const {
    return kLeft + (t - t_.lo) / (t_.hi - t_.lo) * (kWidth - kLeft - kRight);
  }
  [[nodiscard]] double y(double v) const { return top_ + kPanel - (v - y_.lo) / (y_.hi - y_.lo) * kPanel; }

  std::string frame() const {
    std::string s = fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#999"/>)",
                                kLeft, top_, kWidth - kLeft - kRight, kPanel);
    s += fmt::format(R"(<text x="{}" y="{}" font-size="14" font-weight="bold">{}</text>)", kLeft, top_ - 8,
                     title_);
    for (int i = 0; i <= 4; ++i) {
      const double v = y_.lo + (y_.hi - y_.lo) * i / 4.0;
      s += fmt::format(R"(<text x="{}" y="{:.1f}" font-size="11" text-anchor="end">{:.1f} {}</text>)",
                       kLeft - 4, y(v) + 4, v, unit_);
      s += fmt::format(R"(<line x1="{}" y1="{:.1f}" x2="{}" y2="{:.1f}" stroke="#eee"/>)", kLeft, y(v),
                       kWidth - kRight, y(v));
    }
    for (int i = 0; i <= 5; ++i) {
      const double t = t_.lo + (t_.hi - t_.lo) * i / 5.0;
      s += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="11" text-anchor="middle">{:.1f} s</text>)", x(t),
                       top_ + kPanel + 14, t);
    }
    return s;
  }

  template <class Get>
  std::string line(const std::vector<std::pair<double, Sample>>& samples, Get get, const char* colour,
                   const char* dash) const {
    std::string pts;
    for (const auto& [t, s] : samples) pts += fmt::format("{:.1f},{:.1f} ", x(t), y(get(s)));
    return fmt::format(
        R"(<polyline fill="none" stroke="{}" stroke-width="1.5" stroke-dasharray="{}" points="{}"/>)", colour,
        dash, pts);
  }

 private:
  double top_;
  Range t_, y_;
  std::string title_, unit_;
};

std::string legend(double x, double y, const char* colour, const char* dash, const std::string& text) {
  return fmt::format(
      R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="2" stroke-dasharray="{}"/>)"
      R"(<text x="{}" y="{}" font-size="12">{}</text>)",
      x, y, x + 24, y, colour, dash, x + 30, y + 4, text);
}

}  // namespace

std::string render_svg(const std::vector<std::pair<double, Sample>>& samples, const RunSummary& summary) {
  Range t, pos, hz;
  std::uint8_t axes = 0;
  for (const auto& [time, s] : samples) {
    t.add(time);
    axes = std::max(axes, s.axes);
    for (std::uint8_t a = 0; a < s.axes; ++a) pos.add(s.planned_mm[a]), pos.add(s.scu_mm[a]);
    pos.add(s.encoder_mm);
    hz.add(s.spindle_set_hz), hz.add(s.spindle_actual_hz);
  }
  t.pad(), pos.pad(), hz.pad();
  const double height = kTop + 2 * kPanel + kGap + 90;
  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-family="sans-serif">)"
      R"(<rect width="100%" height="100%" fill="white"/>)",
      kWidth, height);
  svg += fmt::format(R"(<text x="{}" y="20" font-size="13">outcome: {} after {:.2f} s, {} faults</text>)",
                     kLeft, summary.outcome(), summary.duration_s(), summary.faults().size());
  const Panel p1(kTop + 10, t, pos, "Axis positions", "mm");
  const Panel p2(kTop + 10 + kPanel + kGap, t, hz, "Spindle frequency", "Hz");
  svg += p1.frame() + p2.frame();
  for (std::uint8_t a = 0; a < axes; ++a) {
    svg += p1.line(
        samples, [a](const Sample& s) { return s.planned_mm[a]; }, kColours[a], "6,3");
    svg += p1.line(
        samples, [a](const Sample& s) { return s.scu_mm[a]; }, kColours[a], "none");
  }
  svg += p1.line(
      samples, [](const Sample& s) { return s.encoder_mm; }, "#000", "2,2");
  svg += p2.line(
      samples, [](const Sample& s) { return s.spindle_set_hz; }, "#ff7f0e", "6,3");
  svg += p2.line(
      samples, [](const Sample& s) { return s.spindle_actual_hz; }, "#ff7f0e", "none");
  const double ly = height - 30;
  double lx = kLeft;
  for (std::uint8_t a = 0; a < axes; ++a) {
    svg += legend(lx, ly, kColours[a], "none", fmt::format("axis {} (SCU)", a + 1));
    svg += legend(lx, ly + 16, kColours[a], "6,3", fmt::format("axis {} planned", a + 1));
    lx += 160;
  }
  svg += legend(lx, ly, "#000", "2,2", "encoder");
  svg += legend(lx + 120, ly, "#ff7f0e", "none", "spindle actual");
  svg += legend(lx + 120, ly + 16, "#ff7f0e", "6,3", "spindle set");
  svg += "</svg>\n";
  return svg;
}

}  // namespace cellctl::journal

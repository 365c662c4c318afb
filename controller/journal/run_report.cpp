#include "journal/run_report.hpp"

#include <fmt/format.h>

#include <cmath>

#include "journal/plot_model.hpp"

namespace cellctl::journal {
namespace {

std::string seconds_or_dash(const std::optional<double>& s) {
  return s ? fmt::format("{:8.2f}", *s) : fmt::format("{:>8}", "—");
}

std::string short_hash(const std::optional<std::string>& hash) {
  return !hash || hash->empty() ? "?" : hash->substr(0, 12);
}

// Per set frequency: how long the spindle took to get within 1 % of it, and how far it strayed after.
std::string spindle_lines(const RunRecord& run) {
  std::string out;
  const auto& ps = run.samples();
  for (std::size_t i = 0; i < ps.size();) {
    const double set = ps[i].spindle_set_hz;
    std::size_t j = i;
    while (j < ps.size() && ps[j].spindle_set_hz == set) ++j;  // [i, j): one set frequency
    if (set > 0.0) {
      std::optional<std::size_t> at_speed;
      double worst = 0.0;
      for (std::size_t k = i; k < j; ++k) {
        const double dev = ps[k].spindle_hz - set;
        if (!at_speed && std::abs(dev) <= 0.01 * set) at_speed = k;
        if (at_speed && std::abs(dev) > std::abs(worst)) worst = dev;
      }
      out +=
          at_speed
              ? fmt::format(
                    "spindle: set {:.1f} Hz at {:.2f} s, within 1 % after {:.2f} s, then within "
                    "{:+.1f} Hz until {:.2f} s\n",
                    set, ps[i].t - run.start(), ps[*at_speed].t - ps[i].t, worst, ps[j - 1].t - run.start())
              : fmt::format(
                    "spindle: set {:.1f} Hz at {:.2f} s, never within 1 % of it (reached {:.1f} Hz)\n", set,
                    ps[i].t - run.start(), ps[j - 1].spindle_hz);
    } else if (i > 0 && ps[i - 1].spindle_set_hz > 0.0) {
      std::size_t k = i;
      while (k < j && ps[k].spindle_hz > 1.0) ++k;
      out += k < j ? fmt::format("spindle: stopped at {:.2f} s, at rest {:.2f} s later\n",
                                 ps[i].t - run.start(), ps[k].t - ps[i].t)
                   : fmt::format("spindle: stopped at {:.2f} s, still at {:.1f} Hz when the record ends\n",
                                 ps[i].t - run.start(), ps[j - 1].spindle_hz);
    }
    i = j;
  }
  return out.empty() ? "spindle: not run\n" : out;
}

}  // namespace

int step_at(const RunRecord& run, double t) {
  int n = 0;
  for (const auto& s : run.steps())
    if (s.start <= t) n = s.step;
  return n;
}

std::vector<MaxFollowingError> max_following_errors(const RunRecord& run) {
  const auto names = run.axis_names();
  std::vector<MaxFollowingError> out(names.size());
  for (std::size_t a = 0; a < names.size(); ++a) {
    const auto err = following_error(run, a);
    for (std::size_t i = 0; i < err.size(); ++i)
      if (!std::isnan(err[i]) && std::abs(err[i]) > std::abs(out[a].mm))
        out[a] = {err[i], run.samples()[i].t, step_at(run, run.samples()[i].t)};
  }
  return out;
}

std::string report_text(const RunRecord& run) {
  const auto& h = run.header();
  std::string out = fmt::format("run of {}\n", run.recipe_label());
  if (run.has_header()) {
    out += fmt::format("  recipe sha256 {}…, config {} sha256 {}…\n", short_hash(h.recipe_sha256),
                       h.config_file.value_or("?"), short_hash(h.config_sha256));
    out += fmt::format("  cellctl {}, {}, host {}, started {}\n", h.cellctl.value_or("?"),
                       h.mode.value_or("?"), h.host.value_or("?"), h.started_utc.value_or("?"));
  }
  out += fmt::format("outcome: {} after {:.2f} s\n\n", run.outcome(), run.duration_s());

  out += fmt::format("{:>4}  {:<52} {:>8} {:>8} {:>8}  {}\n", "step", "label", "planned", "actual", "held",
                     "result");
  for (const auto& s : run.steps()) {
    std::string label = s.label.size() > 52 ? s.label.substr(0, 51) + "…" : s.label;
    out += fmt::format("{:>4}  {:<52} {} {:8.2f} {:>8}  {}{}\n", s.step, label,
                       seconds_or_dash(run.planned_s(s)), s.seconds(),
                       s.held_s > 0 ? fmt::format("{:.2f}", s.held_s) : "", s.result,
                       s.detail.empty() ? "" : ": " + s.detail);
  }
  out += "  (planned: a move's profile, a dwell's time; — where nothing is planned, as a spindle ramp)\n\n";

  int faults = 0;
  for (const auto& m : run.marks()) {
    if (m.kind == MarkKind::fault || m.kind == MarkKind::injected_fault) ++faults;
    out += fmt::format("{:9.3f} s  {:<15} {}\n", m.t - run.start(), to_string(m.kind), m.text);
  }
  if (run.marks().empty()) out += "no faults, no operator commands, no notes\n";
  out += fmt::format("{} fault{}\n\n", faults, faults == 1 ? "" : "s");

  const auto names = run.axis_names();
  const auto measured = run.measured_axis();
  const auto worst = max_following_errors(run);
  out += "max following error (planned − measured, during moves):\n";
  for (std::size_t a = 0; a < names.size(); ++a)
    out += fmt::format("  {:<6} {:+8.3f} mm at {:.2f} s (step {}), against the {}\n", names[a], worst[a].mm,
                       worst[a].t - run.start(), worst[a].step, measured == a ? "encoder" : "SCU");

  if (const auto& loop = run.loop_figures())
    out += fmt::format(
        "loop: {} cycles, wake-up jitter p99 {:.1f} µs, {} overrun cycles, {} missed deadlines, {} journal "
        "events dropped\n",
        loop->cycles, loop->jitter_p99_us, loop->overrun_cycles, loop->missed_deadlines,
        loop->journal_dropped);
  else
    out += "loop: no summary line (the run did not end normally)\n";
  out += spindle_lines(run);
  return out;
}

void write_csv(const RunRecord& run, std::ostream& out) {
  const auto names = run.axis_names();
  const bool encoder = run.measured_axis().has_value();
  out << "t_s,step";
  for (const auto& n : names) out << ',' << n << "_planned_mm," << n << "_scu_mm";
  if (encoder) out << ",encoder_mm";
  out << ",spindle_set_hz,spindle_hz\n";
  for (const auto& p : run.samples()) {
    out << fmt::format("{:.3f},{}", p.t - run.start(), step_at(run, p.t));
    for (std::size_t a = 0; a < names.size(); ++a)
      out << fmt::format(",{},{}", a < p.planned_mm.size() ? fmt::format("{:.4f}", p.planned_mm[a]) : "",
                         a < p.scu_mm.size() ? fmt::format("{:.4f}", p.scu_mm[a]) : "");
    if (encoder) out << fmt::format(",{:.4f}", p.encoder_mm);
    out << fmt::format(",{:.2f},{:.2f}\n", p.spindle_set_hz, p.spindle_hz);
  }
}

}  // namespace cellctl::journal

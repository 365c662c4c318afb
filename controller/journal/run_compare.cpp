#include "journal/run_compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "journal/plot_model.hpp"

namespace cellctl::journal {
namespace {

// Where each axis ended against its plan (planned − measured) at the step's end.
std::vector<double> end_errors(const RunRecord& run, const StepRun& s) {
  std::vector<double> out;
  const auto* p = run.sample_at(s.end);
  const auto measured = run.measured_axis();
  if (!p) return out;
  for (std::size_t a = 0; a < p->planned_mm.size(); ++a)
    out.push_back(p->planned_mm[a] - (measured == a ? p->encoder_mm : p->scu_mm[a]));
  return out;
}

double spindle_at_end(const RunRecord& run, const StepRun& s) {
  const auto* p = run.sample_at(s.end);
  return p ? p->spindle_hz : 0.0;
}

const StepRun* find_step(const RunRecord& run, int n) {
  for (const auto& s : run.steps())
    if (s.step == n) return &s;
  return nullptr;
}

}  // namespace

std::optional<std::string> different_recipes(const RunRecord& a, const RunRecord& b) {
  const auto ha = a.header().recipe_sha256.value_or("");
  const auto hb = b.header().recipe_sha256.value_or("");
  if (!ha.empty() && !hb.empty()) {
    if (ha == hb) return std::nullopt;
    return fmt::format("the recipes differ: A is {} (sha256 {}…), B is {} (sha256 {}…)", a.recipe_label(),
                       ha.substr(0, 12), b.recipe_label(), hb.substr(0, 12));
  }
  const auto na = a.header().recipe.value_or("");
  const auto nb = b.header().recipe.value_or("");
  if (!na.empty() && na == nb) return std::nullopt;
  return fmt::format("cannot tell that both are runs of one recipe (A: {}, B: {})", a.recipe_label(),
                     b.recipe_label());
}

std::string compare_text(const RunRecord& a, const RunRecord& b) {
  std::string out = fmt::format("A: {} — {} after {:.2f} s, {}\nB: {} — {} after {:.2f} s, {}\n\n",
                                a.recipe_label(), a.outcome(), a.duration_s(), a.header().mode.value_or("?"),
                                b.recipe_label(), b.outcome(), b.duration_s(), b.header().mode.value_or("?"));
  const auto names = a.axis_names();
  out += fmt::format("{:>4}  {:<30} {:>7} {:>7} {:>7}", "step", "label", "A s", "B s", "B−A s");
  for (const auto& n : names) out += fmt::format("  {:>15}", n + " end err A/B");
  out += fmt::format("  {:>15}\n", "spindle A/B Hz");
  int last = 0;
  for (const auto& s : a.steps()) last = std::max(last, s.step);
  for (const auto& s : b.steps()) last = std::max(last, s.step);
  double total_delta = 0.0;
  for (int n = 1; n <= last; ++n) {
    const auto* sa = find_step(a, n);
    const auto* sb = find_step(b, n);
    const auto& label = sa ? sa->label : sb ? sb->label : std::string("?");
    std::string name = short_step_name(label);
    if (name.size() > 30) name = name.substr(0, 29) + "…";
    if (!sa || !sb) {
      out += fmt::format("{:>4}  {:<30} only in {}\n", n, name, sa ? "A" : "B");
      continue;
    }
    total_delta += sb->seconds() - sa->seconds();
    out += fmt::format("{:>4}  {:<30} {:7.2f} {:7.2f} {:+7.2f}", n, name, sa->seconds(), sb->seconds(),
                       sb->seconds() - sa->seconds());
    const auto ea = end_errors(a, *sa), eb = end_errors(b, *sb);
    for (std::size_t i = 0; i < names.size(); ++i)
      out += fmt::format("  {:>7} {:>7}", i < ea.size() ? fmt::format("{:+.3f}", ea[i]) : "—",
                         i < eb.size() ? fmt::format("{:+.3f}", eb[i]) : "—");
    out += fmt::format("  {:7.1f} {:7.1f}", spindle_at_end(a, *sa), spindle_at_end(b, *sb));
    if (sa->result != "done" || sb->result != "done")
      out += fmt::format("  (A {}, B {})", sa->result, sb->result);
    out += "\n";
  }
  out += fmt::format(
      "total: B took {:+.2f} s against A over the steps both ran ({:.2f} s against {:.2f} s overall)\n",
      total_delta, b.duration_s(), a.duration_s());
  out +=
      "end err: planned − measured (encoder where it measures the axis, else the SCU) at the step's end, "
      "mm\n";
  return out;
}

}  // namespace cellctl::journal

#include "motion/planned_time.hpp"

#include <array>
#include <cmath>
#include <variant>

#include "cell/cell_state.hpp"
#include "motion/move_limits.hpp"
#include "planner/planner.hpp"

namespace cellctl::motion {
namespace {

// The converter's time from `from` to `to` Hz (signed by direction): down to rest first when the
// direction changes or it stops, then up.
double ramp_s(double from, double to, const SpindleRamps& r) {
  const bool same_way = from * to > 0.0;
  if (same_way)
    return std::abs(to) >= std::abs(from) ? (std::abs(to) - std::abs(from)) / r.up_hz_s
                                          : (std::abs(from) - std::abs(to)) / r.down_hz_s;
  return std::abs(from) / r.down_hz_s + std::abs(to) / r.up_hz_s;
}

}  // namespace

recipe::PlannedTime planned_time(const config::CellCore& cell, const recipe::Program& program,
                                 std::span<const std::optional<double>> start_mm,
                                 const std::optional<SpindleRamps>& spindle) {
  recipe::PlannedTime out;
  std::array<std::optional<double>, cellctl::cell::kMaxAxes> at{};
  for (std::size_t i = 0; i < start_mm.size() && i < at.size(); ++i) at[i] = start_mm[i];
  double spindle_hz = 0.0;  // a job starts with the spindle at rest
  planner::Planner<6> planner(cell.loop.period_ms / 1000.0);
  for (const auto& ins : program.instructions) {
    if (const auto* m = std::get_if<recipe::Move>(&ins.action)) {
      planner::Input<6> in;
      in.synchronization =
          m->path == recipe::Path::line ? planner::Synchronization::phase : planner::Synchronization::time;
      in.enabled.fill(false);
      bool known = true;
      for (std::size_t i = 0; i < cell.axes.size() && i < at.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        in.current_position[k] = in.target_position[k] = at[i].value_or(0.0);
        limit_axis(cell, m->speed_mm_s, i, in);
      }
      for (const auto& t : m->targets) {
        const auto i = static_cast<std::size_t>(t.axis);
        known = known && at[i].has_value();
        in.enabled[i] = true;
        in.target_position[static_cast<Eigen::Index>(i)] = t.target_mm;
        at[i] = t.target_mm;
      }
      planner::Output<6> o;
      if (!known || planner::is_error(planner.update(in, o))) {
        ++out.not_counted;
        continue;
      }
      out.seconds += planner.trajectory().duration();
    } else if (const auto* d = std::get_if<recipe::Dwell>(&ins.action)) {
      out.seconds += d->seconds;
    } else if (const auto* sp = std::get_if<recipe::Spindle>(&ins.action)) {
      const double want = !sp->start                                      ? 0.0
                          : sp->direction == recipe::SpindleDirection::cw ? sp->frequency_hz
                                                                          : -sp->frequency_hz;
      if (spindle && spindle->up_hz_s > 0.0 && spindle->down_hz_s > 0.0)
        out.seconds += ramp_s(spindle_hz, want, *spindle);
      else
        ++out.not_counted;
      spindle_hz = want;
    } else if (std::holds_alternative<recipe::Require>(ins.action)) {
      // checked at once
    } else {
      // A wait, a homing, a Teach-In: the cell tells when they end. A homed axis ends where its homing
      // puts it, which the plan does not know either.
      ++out.not_counted;
      if (const auto* h = std::get_if<recipe::Home>(&ins.action))
        for (const int a : h->axes) at[static_cast<std::size_t>(a)].reset();
      if (const auto* t = std::get_if<recipe::TeachIn>(&ins.action))
        at[static_cast<std::size_t>(t->axis)].reset();
    }
  }
  return out;
}

}  // namespace cellctl::motion

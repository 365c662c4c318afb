#include "planner/travel_fit.hpp"

#include <algorithm>
#include <cmath>

#include "planner/axis_profile.hpp"
#include "planner/brake.hpp"

namespace cellctl::planner {

TravelExcess travel_excess(const JerkProfile& p, double min_position, double max_position) noexcept {
  const PositionExtrema e = p.extrema();
  const double below = min_position - e.min.position;
  const double above = e.max.position - max_position;
  return TravelExcess{above >= below, std::max(above, below)};
}

JerkProfile mix(const JerkProfile& x, const JerkProfile& y, double w) noexcept {
  JerkProfile out(x.start());
  std::size_t ix = 0;
  std::size_t iy = 0;
  double left_x = x.size() > 0 ? x.segment(0).duration : 0.0;
  double left_y = y.size() > 0 ? y.segment(0).duration : 0.0;
  // One piece per stretch in which neither jerk changes; the last stretch of the longer one (by
  // rounding only) is taken with the other's jerk at zero.
  while (ix < x.size() || iy < y.size()) {
    const double jx = ix < x.size() ? x.segment(ix).jerk : 0.0;
    const double jy = iy < y.size() ? y.segment(iy).jerk : 0.0;
    double piece = 0.0;
    if (ix < x.size() && iy < y.size()) {
      piece = std::min(left_x, left_y);
    } else {
      piece = ix < x.size() ? left_x : left_y;
    }
    out.append({(1.0 - w) * jx + w * jy, piece});
    left_x -= piece;
    left_y -= piece;
    if (ix < x.size() && left_x <= 0.0 && ++ix < x.size()) left_x = x.segment(ix).duration;
    if (iy < y.size() && left_y <= 0.0 && ++iy < y.size()) left_y = y.segment(iy).duration;
  }
  return out;
}

JerkProfile nearest_inside(const JerkProfile& inside, const JerkProfile& outside, double min_position,
                           double max_position) noexcept {
  // The excess is convex in w, at most `bound` at 0 and above it at 1: bisection keeps w_in there.
  const double bound = std::max(0.0, travel_excess(inside, min_position, max_position).by);
  double w_in = 0.0;
  double w_out = 1.0;
  JerkProfile best = inside;
  for (int i = 0; i < 60 && w_out - w_in > 1e-12; ++i) {
    const double w = (w_in + w_out) / 2.0;
    JerkProfile m = mix(inside, outside, w);
    if (travel_excess(m, min_position, max_position).by <= bound) {
      w_in = w;
      best = m;
    } else {
      w_out = w;
    }
  }
  return best;
}

bool turn_first(const MotionState& start, const MotionState& target, const AxisLimits& limits,
                bool towards_max, JerkProfile& out) noexcept {
  if (!is_safe(start.velocity, start.acceleration, limits)) return false;
  // In the frame where the motion goes towards max_position.
  const double sign = towards_max ? 1.0 : -1.0;
  const AxisLimits l = towards_max ? limits : limits.mirrored();
  const double v = sign * start.velocity;
  const double a = std::max(sign * start.acceleration, l.min_acceleration);
  const double j = l.jerk;
  if (!(v > 0.0)) return false;
  // -J until the velocity is zero (v + a t - J t^2 / 2 = 0) or the acceleration at its bound.
  const double ramp = (a - l.min_acceleration) / j;
  const double to_zero = (a + std::sqrt(a * a + 2.0 * j * v)) / j;
  JerkProfile turn(start);
  if (to_zero <= ramp) {
    turn.append({-sign * j, to_zero});
  } else {
    const double left = v + a * ramp - j * ramp * ramp / 2.0;  // > 0
    turn.append({-sign * j, ramp});
    turn.append({0.0, left / -l.min_acceleration});
  }
  // Turning further than ramping the acceleration out can undo would cross the opposite velocity
  // limit (tight limits): no such turn. Each state of the turn is safer than its end (the velocity
  // and the acceleration only fall), so a safe end keeps the limits throughout.
  if (!is_safe(turn.end().velocity, turn.end().acceleration, limits)) return false;
  AxisProfile rest;
  if (rest.plan(turn.end(), target, limits) != AxisStatus::ok) return false;
  JerkProfile from_turn;
  if (!rest.build(rest.min_duration(), from_turn)) return false;
  out = turn;
  for (std::size_t k = 0; k < from_turn.size(); ++k) out.append(from_turn.segment(k));
  return true;
}

}  // namespace cellctl::planner

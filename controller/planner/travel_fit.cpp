#include "planner/travel_fit.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace cellctl::planner

#include "planner/rest_to_rest.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::planner {
namespace {

// Time to change the velocity by v (> 0) from and to zero acceleration, peak acceleration `a`:
// a trapezoid (a / J + v / a) when v reaches a^2 / J, a triangle (2 sqrt(v / J)) otherwise. The
// distance covered while changing from 0 to v is v times half this time (the shape is
// point-symmetric about its middle). Written as its ramp min(a / J, sqrt(v / J)) plus the larger of
// v / a and sqrt(v / J) (the same sums): a min and a max where a branch on a^2 / J was mispredicted
// on a third of the calls (the limits differ from axis to axis).
double change_time(double v, double a, double j) noexcept {
  const double s = std::sqrt(v / j);
  return std::min(a / j, s) + std::max(v / a, s);
}

// rest_to_rest_time with one acceleration bound `a` both ways (symmetric limits: every plan of
// Trajectory::plan_rest_to_rest). Both velocity changes are then one shape, and each case has its
// duration in a form without cancellation: a third of the divisions of the general form, which sat
// on the plan's critical path (a third of a plan from rest in time, a tenth in instructions).
double symmetric_time(double d, double vmax, double a, double j) noexcept {
  const double ramp = a / j;  // ramping the acceleration in (or out)
  const double to_vmax = change_time(vmax, a, j);
  // Reaching max_velocity (to_vmax there, as long back) covers vmax to_vmax; the rest is cruised.
  if (vmax * to_vmax <= d) return to_vmax + d / vmax;
  // Below max_velocity at a peak v: with x = v / a (the plateau's time plus one ramp),
  // d = a x (x + ramp) and T = 2 (x + ramp) = ramp + sqrt(ramp^2 + 4 d / a); where the peak is
  // too low for a plateau (d < 2 a ramp^2), triangles: d = 2 J tau^3, T = 4 tau.
  if (d < 2.0 * a * ramp * ramp) return 4.0 * std::cbrt(d / (2.0 * j));
  return ramp + std::sqrt(ramp * ramp + 4.0 * d / a);
}

}  // namespace

double rest_to_rest_time(double distance, const AxisLimits& limits) noexcept {
  if (distance == 0.0) return 0.0;
  const double d = std::abs(distance);
  // Tested before the direction, which a symmetric axis does not need (its sign is a coin toss).
  if (limits.min_velocity == -limits.max_velocity && limits.min_acceleration == -limits.max_acceleration)
    return symmetric_time(d, limits.max_velocity, limits.max_acceleration, limits.jerk);
  const bool forward = distance > 0.0;
  const double vmax = forward ? limits.max_velocity : -limits.min_velocity;
  const double a_up = forward ? limits.max_acceleration : -limits.min_acceleration;
  const double a_down = forward ? -limits.min_acceleration : limits.max_acceleration;
  const double j = limits.jerk;
  const auto covered = [&](double v) {
    return v * (change_time(v, a_up, j) + change_time(v, a_down, j)) / 2.0;
  };
  const double at_vmax = covered(vmax);
  if (at_vmax <= d) return change_time(vmax, a_up, j) + change_time(vmax, a_down, j) + (d - at_vmax) / vmax;
  // The peak velocity v < vmax with covered(v) = d. covered grows with v and its form changes where
  // each ramp gets its plateau: solve in the piece that contains d.
  const double a_lo = std::min(a_up, a_down);
  const double a_hi = std::max(a_up, a_down);
  const double v1 = a_lo * a_lo / j;  // below: no plateau at all
  const double v2 = a_hi * a_hi / j;  // above: both plateaus
  double v = 0.0;
  if (d <= covered(v1)) {
    v = std::cbrt(d * d * j / 4.0);  // d = 2 v sqrt(v / J)
  } else if (d >= covered(v2)) {
    // d = v/2 (v (1/a_up + 1/a_down) + (a_up + a_down)/J): a quadratic, in its non-cancelling form.
    const double qa = (1.0 / a_up + 1.0 / a_down) / 2.0;
    const double qb = (a_up + a_down) / (2.0 * j);
    v = 2.0 * d / (qb + std::sqrt(qb * qb + 4.0 * qa * d));
  } else {
    // One plateau (on the ramp with the smaller bound): d = v/2 (v/a_lo + a_lo/J + 2 sqrt(v/J)).
    // Newton on w = sqrt(v), from the right end of the piece (convex and increasing: no overshoot).
    double w = std::sqrt(v2);
    const double sj = std::sqrt(j);
    for (int i = 0; i < 50; ++i) {
      const double w2 = w * w;
      const double f = w2 / 2.0 * (w2 / a_lo + a_lo / j + 2.0 * w / sj) - d;
      const double df = 2.0 * w2 * w / a_lo + w * a_lo / j + 3.0 * w2 / sj;
      const double next = w - f / df;
      if (!(next < w)) break;
      w = next;
    }
    v = w * w;
  }
  return change_time(v, a_up, j) + change_time(v, a_down, j);
}

double rest_to_rest_farthest(double T, const AxisLimits& limits, SevenDurations& t) noexcept {
  const double vmax = limits.max_velocity;
  const double amax = limits.max_acceleration;
  const double j = limits.jerk;
  const double to_vmax = change_time(vmax, amax, j);  // from rest to max_velocity
  double ramp = 0.0;
  double hold = 0.0;
  if (T >= 2.0 * to_vmax) {
    // The ramp and the hold of change_time, each without a branch (where the hold is none it comes
    // out below zero).
    ramp = std::min(amax / j, std::sqrt(vmax / j));
    hold = std::max(0.0, vmax / amax - amax / j);
    const double cruise = T - 2.0 * to_vmax;
    t = SevenDurations{ramp, hold, ramp, cruise, ramp, hold, ramp};
    return vmax * (to_vmax + cruise);
  }
  const double half = T / 2.0;
  double peak = 0.0;
  if (half >= 2.0 * amax / j) {
    ramp = amax / j;
    hold = half - 2.0 * ramp;
    peak = amax * (ramp + hold);
  } else {
    ramp = half / 2.0;
    peak = j * ramp * ramp;
  }
  t = SevenDurations{ramp, hold, ramp, 0.0, ramp, hold, ramp};
  return peak * half;
}

bool rest_to_rest_pieces(double T, bool shortest, double distance, const AxisLimits& limits,
                         std::array<JerkSegment, kFarthestJerkSigns.size()>& pieces) noexcept {
  SevenDurations up{};
  const double far = rest_to_rest_farthest(T, limits, up);
  if (std::isnan(far)) return false;
  // The share of the farthest profile's jerk in the blend that ends exactly at the distance (the
  // nearest profile is the farthest one mirrored, so the blend is the farthest profile scaled). The
  // shortest duration's profile is the farthest one on the distance's side, share 1 or 0 exactly
  // (the other side's share would only be rounding), unless it misses the distance by more than
  // rounding (then the blend ends on it). One formula for all three: a share of 1 or 0 gives the
  // farthest profile on either side exactly. (Not faster than the three branches it replaced, the
  // same mispredicts by callgrind: simpler.)
  const double blend = far > 0.0 ? std::clamp((distance + far) / (far + far), 0.0, 1.0) : 1.0;
  const bool own = shortest && std::abs(std::abs(distance) - far) <= 1e-13 * (1.0 + std::abs(distance));
  const double side = distance >= 0.0 ? 1.0 : 0.0;
  const double share = own ? side : blend;
  // j (share s - (1 - share) s) for the signs s = 1, 0, -1, worked out once per sign (share 1 or 0
  // gives j and -j exactly).
  const double j = limits.jerk;
  const double rise = j * (share - (1.0 - share));
  const double fall = j * ((1.0 - share) - share);
  pieces = {JerkSegment{rise, up[0]}, JerkSegment{0.0, up[1]},  JerkSegment{fall, up[2]},
            JerkSegment{0.0, up[3]},  JerkSegment{fall, up[4]}, JerkSegment{0.0, up[5]},
            JerkSegment{rise, up[6]}};
  return true;
}

}  // namespace cellctl::planner

#include "planner/profile_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::planner {

JerkProfile rest_to_rest(double distance, const AxisLimits& limits) noexcept {
  JerkProfile profile(MotionState{});
  if (distance == 0.0) return profile;
  const double sign = distance > 0.0 ? 1.0 : -1.0;
  const double d = std::abs(distance);
  const double v_max = limits.velocity;
  const double a_max = limits.acceleration;
  const double j = limits.jerk;
  // Below this peak velocity the acceleration ramp has no constant part (a_max is never reached).
  const double v_without_plateau = a_max * a_max / j;

  double tj = 0.0;  // each jerk segment
  double ta = 0.0;  // each constant-acceleration segment
  double tv = 0.0;  // the cruise at v_max
  // Acceleration phase up to peak velocity vp; the move covers vp * (2 tj + ta) to get there and
  // back to rest (the phase is symmetric, so its mean velocity is vp / 2).
  const auto shape_for_peak = [&](double vp) {
    if (vp >= v_without_plateau) {
      tj = a_max / j;
      ta = vp / a_max - tj;
    } else {
      tj = std::sqrt(vp / j);
      ta = 0.0;
    }
  };
  shape_for_peak(v_max);
  const double d_at_v_max = v_max * (2.0 * tj + ta);
  if (d_at_v_max <= d) {
    tv = (d - d_at_v_max) / v_max;
  } else {
    // v_max is never reached. With a plateau: vp^2 + vp a^2/j - a d = 0, solved in the form that
    // does not cancel; without one: d = 2 j tj^3.
    const double c = a_max * a_max / j;
    const double vp = 2.0 * a_max * d / (c + std::sqrt(c * c + 4.0 * a_max * d));
    if (vp >= v_without_plateau) {
      tj = a_max / j;
      ta = std::max(0.0, vp / a_max - tj);
    } else {
      tj = std::cbrt(d / (2.0 * j));
      ta = 0.0;
    }
  }
  const double js = sign * j;
  profile.append({js, tj});
  profile.append({0.0, ta});
  profile.append({-js, tj});
  profile.append({0.0, tv});
  profile.append({-js, tj});
  profile.append({0.0, ta});
  profile.append({js, tj});
  return profile;
}

JerkProfile brake_to_rest(const MotionState& start, const AxisLimits& limits) noexcept {
  JerkProfile profile(start);
  const double j = limits.jerk;
  const double a_max = limits.acceleration;
  // The velocity reached if the acceleration were ramped to zero right now at full jerk: its sign
  // says which way the braking acceleration has to point.
  const double v_ramp = start.velocity + start.acceleration * std::abs(start.acceleration) / (2.0 * j);
  if (v_ramp == 0.0) {
    profile.append({start.acceleration > 0.0 ? -j : j, std::abs(start.acceleration) / j});
    return profile;
  }
  // Work in the frame where the motion to stop is positive, so braking means negative acceleration.
  const double dir = v_ramp > 0.0 ? 1.0 : -1.0;
  const double v = dir * start.velocity;
  const double a = dir * start.acceleration;
  const double ramp = dir * v_ramp;

  double a_peak = 0.0;  // magnitude of the braking acceleration
  double t1 = 0.0;      // from a to -a_peak
  double j1 = -j;
  double t2 = 0.0;  // hold -a_peak
  if (a < -a_max) {
    // Already braking harder than allowed: ease back to -a_max, hold, release.
    a_peak = a_max;
    j1 = j;
    t1 = (-a - a_max) / j;
    t2 = ramp / a_max;
  } else {
    // From v + a^2/2j - a_peak^2/j - a_peak t2 = 0: without a hold, a_peak = sqrt(j v + a^2/2).
    a_peak = std::min(std::sqrt(std::max(0.0, j * v + a * a / 2.0)), a_max);
    t1 = std::max(0.0, (a + a_peak) / j);
    t2 = std::max(0.0, (v + a * a / (2.0 * j) - a_peak * a_peak / j) / a_peak);
  }
  profile.append({dir * j1, t1});
  profile.append({0.0, t2});
  profile.append({dir * j, a_peak / j});
  return profile;
}

}  // namespace cellctl::planner

#include "planner/brake.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::planner {
namespace {

// Rounding allowance: the planner's own outputs fed back may sit an ulp outside a bound.
double tolerance(double bound) noexcept {
  return 1e-12 * (1.0 + std::abs(bound));
}

bool over_max(double v, double a, const AxisLimits& l) noexcept {
  // Beyond max_velocity, or bound to cross it (a > 0): one test on v plus the ramp, zero for a <= 0
  // (v + ramp >= v, so it covers both; a branch on the sign of a was a misprediction in two).
  const double rising = std::max(0.0, a);
  return v + rising * rising / (2.0 * l.jerk) > l.max_velocity + tolerance(l.max_velocity);
}

// Full negative jerk, the acceleration held at min_acceleration, until v is back at max_velocity.
// `sign` +1 brakes from above max_velocity; -1 is the mirror (from below min_velocity).
void brake_down(JerkProfile& profile, const AxisLimits& l, double sign) noexcept {
  const double v = sign * profile.end().velocity;
  const double a = sign * profile.end().acceleration;
  const double j = l.jerk;
  const double to_floor = (a - l.min_acceleration) / j;
  // v + a t - j t^2 / 2 = max_velocity, the later (falling) crossing.
  const double t = (a + std::sqrt(std::max(0.0, a * a + 2.0 * j * (v - l.max_velocity)))) / j;
  if (t <= to_floor) {
    profile.append({-sign * j, t});
    return;
  }
  profile.append({-sign * j, to_floor});
  const double v1 = sign * profile.end().velocity;
  profile.append({0.0, (v1 - l.max_velocity) / -l.min_acceleration});
}

}  // namespace

bool is_safe(double v, double a, const AxisLimits& l) noexcept {
  const double ta = tolerance(l.max_acceleration - l.min_acceleration);
  return a <= l.max_acceleration + ta && a >= l.min_acceleration - ta && !over_max(v, a, l) &&
         !over_max(-v, -a, l.mirrored());
}

JerkProfile brake_profile(const MotionState& start, const AxisLimits& l) noexcept {
  JerkProfile profile(start);
  const double a = start.acceleration;
  if (a > l.max_acceleration) profile.append({-l.jerk, (a - l.max_acceleration) / l.jerk});
  if (a < l.min_acceleration) profile.append({l.jerk, (l.min_acceleration - a) / l.jerk});
  const MotionState s = profile.end();
  if (over_max(s.velocity, s.acceleration, l)) {
    brake_down(profile, l, 1.0);
  } else if (over_max(-s.velocity, -s.acceleration, l.mirrored())) {
    brake_down(profile, l.mirrored(), -1.0);
  }
  return profile;
}

}  // namespace cellctl::planner

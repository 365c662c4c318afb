#include "planner/brake.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace cellctl::planner {
namespace {

// Rounding allowance: the planner's own outputs fed back may sit an ulp outside a bound.
double tolerance(double bound) noexcept {
  return 1e-12 * (1.0 + std::abs(bound));
}

// half_inv_jerk is 0.5 / l.jerk: one division for both tests (a division is several
// multiplications' time).
bool over_max(double v, double a, const AxisLimits& l, double half_inv_jerk) noexcept {
  // Beyond max_velocity, or bound to cross it (a > 0): one test on v plus the ramp, zero for a <= 0
  // (v + ramp >= v, so it covers both; a branch on the sign of a was a misprediction in two).
  // max(0, a) exactly, without the branch g++ made of std::max there (folding the square into it).
  const double rising = 0.5 * (a + std::abs(a));
  return v + rising * rising * half_inv_jerk > l.max_velocity + tolerance(l.max_velocity);
}

// Brakes a state over max_velocity (the acceleration within its bounds) into the safe states; `sign`
// -1 is the mirror (under min_velocity, `l` mirrored). Full negative jerk keeps the velocity the
// acceleration ramps out to, c = v + a^2 / 2J, while the acceleration turns, and the velocity then
// falls as c - a^2 / 2J. That ramp ends at the first of:
// - the velocity back at max_velocity: a = -sqrt(2J (c - max_velocity)), a safe state;
// - ramping out from there would end at min_velocity (v - a^2 / 2J = min_velocity):
//   a = -sqrt(J (c - min_velocity)). The velocity, still above max_velocity, falls on along that
//   boundary at full positive jerk (which keeps v - a^2 / 2J) until it is back at max_velocity;
// - min_acceleration, held until the velocity is back at max_velocity or on that boundary.
void brake_velocity(JerkProfile& profile, const AxisLimits& l, double sign) noexcept {
  const double v = sign * profile.end().velocity;
  const double a = sign * profile.end().acceleration;
  const double j = l.jerk;
  const double c = v + a * a / (2.0 * j);
  const double at_max = -std::sqrt(std::max(0.0, 2.0 * j * (c - l.max_velocity)));
  const double on_boundary = -std::sqrt(std::max(0.0, j * (c - l.min_velocity)));
  // Where the boundary (ramping out ends at min_velocity) meets max_velocity.
  const double boundary_at_max = -std::sqrt(2.0 * j * (l.max_velocity - l.min_velocity));
  std::array<JerkSegment, 3> segments{};
  // Nested, not the initializer-list max: that one loops, with a branch per value.
  const double ramp_end = std::max(std::max(at_max, on_boundary), l.min_acceleration);
  segments[0] = {-sign * j, std::max(0.0, (a - ramp_end) / j)};
  if (ramp_end == on_boundary && on_boundary > at_max) {
    segments[1] = {sign * j, (boundary_at_max - on_boundary) / j};
  } else if (ramp_end == l.min_acceleration && l.min_acceleration > at_max) {
    const double floor = l.min_acceleration;
    const double held_from = c - floor * floor / (2.0 * j);
    const double boundary_at_floor = l.min_velocity + floor * floor / (2.0 * j);
    segments[1] = {0.0, std::max(0.0, (held_from - std::max(l.max_velocity, boundary_at_floor)) / -floor)};
    if (boundary_at_floor > l.max_velocity) segments[2] = {sign * j, (boundary_at_max - floor) / j};
  }
  profile.append(segments.data(), segments.size());
}

}  // namespace

bool is_safe(double v, double a, const AxisLimits& l) noexcept {
  const double ta = tolerance(l.max_acceleration - l.min_acceleration);
  const double half_inv_jerk = 0.5 / l.jerk;
  return a <= l.max_acceleration + ta && a >= l.min_acceleration - ta && !over_max(v, a, l, half_inv_jerk) &&
         !over_max(-v, -a, l.mirrored(), half_inv_jerk);
}

void brake_profile(const MotionState& start, const AxisLimits& l, JerkProfile& profile) noexcept {
  profile = JerkProfile(start);
  const double a = start.acceleration;
  if (a > l.max_acceleration) profile.append({-l.jerk, (a - l.max_acceleration) / l.jerk});
  if (a < l.min_acceleration) profile.append({l.jerk, (l.min_acceleration - a) / l.jerk});
  const MotionState s = profile.end();
  const double half_inv_jerk = 0.5 / l.jerk;
  const bool over = over_max(s.velocity, s.acceleration, l, half_inv_jerk);
  const bool under = over_max(-s.velocity, -s.acceleration, l.mirrored(), half_inv_jerk);
  // Beyond one side and bound to cross the other: the acceleration decides (it is what crosses).
  if (over && (!under || s.acceleration > 0.0)) {
    brake_velocity(profile, l, 1.0);
  } else if (under) {
    brake_velocity(profile, l.mirrored(), -1.0);
  }
}

}  // namespace cellctl::planner

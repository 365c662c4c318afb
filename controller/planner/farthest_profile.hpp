#pragma once
// For one axis from a state inside its limits: the profile of a given duration T that ends in a
// given velocity and acceleration and gets as far as possible in the positive direction.
//
// Why this is the building block (our reading of the maths; how it is used: axis_profile.hpp):
// - The states reachable at time T form a convex set (linear dynamics, convex bounds on jerk,
//   acceleration and velocity), so for a fixed end velocity and acceleration the reachable end
//   positions are an interval [nearest(T), farthest(T)]. A duration T is feasible for a target
//   position exactly when the target lies in that interval, and any target inside it is reached by
//   blending the two extreme profiles' jerks (linear in the jerk, convex in the bounds).
// - By the maximum principle the farthest profile drives the jerk +J, -J, +J, with arcs where a
//   bound is active: +J, hold max_acceleration, -J, cruise at max_velocity, -J, hold
//   min_acceleration, +J. Given T, the (at most two) free acceleration levels follow from the end
//   velocity and T in closed form (a linear or quadratic equation per set of active bounds).
// - The nearest profile is the farthest one of the mirrored problem.

#include <array>

#include "planner/axis_limits.hpp"

namespace cellctl::planner {

// Jerk signs of the seven segments of a farthest profile (in units of the jerk limit).
inline constexpr std::array<double, 7> kFarthestJerkSigns{1.0, 0.0, -1.0, 0.0, -1.0, 0.0, 1.0};

using SevenDurations = std::array<double, 7>;

// The shortest time in which (v0, a0) can become (vf, af) within the limits (the reach time), and
// the distance covered in it: only one profile is that fast, so the farthest and the nearest
// position at the reach time are this one. Both states must be inside the limits (see is_safe in
// brake.hpp); the time is infinite (the distance NaN) when no such change exists.
// The profile itself is kept too (an axis blends its stop to rest with an extreme, see
// AxisProfile::prepare): jerk direction * J for ramp_in, its peak acceleration held for `hold`,
// -direction * J for ramp_out (direction -1 when the acceleration falls first).
// A plain aggregate (no default member values): an axis's stop is then not zeroed for every axis
// planned before plan() sets it.
struct Reach {
  double time;
  double position;
  double direction;
  double ramp_in;
  double hold;
  double ramp_out;
};
[[nodiscard]] Reach reach(double v0, double a0, double vf, double af, const AxisLimits& limits) noexcept;
// reach() to rest (vf = af = 0), the stop an axis blends to a target at rest: the same values, bit
// for bit, with the zeros folded in where that keeps the values, and away from a tie only the rise
// that can stop worked out (see the definition).
[[nodiscard]] Reach stop_to_rest(double v0, double a0, const AxisLimits& limits) noexcept;

// Durations (lo, hi) in which (v0, a0) cannot become (vf, af), the position ignored. With a0 and af
// of one sign, say both >= 0, the least velocity change in T is made by dipping the acceleration
// to m = (a0 + af - J T) / 2 and back: (a0^2 + af^2 - 2 m^2) / 2J, which first grows with T (while
// m > 0) and only then falls. A change vf - v0 below its peak is reachable for short T, then not
// while the least change exceeds it, then again: the gap between the two roots m = ±sqrt(...),
// the lower one held at min_acceleration. (The mirror for both <= 0.) lo >= hi: no gap. A gap that
// would start at the shortest acceleration change |af - a0| / J comes back as lo = 0: nothing is
// reachable before its end. The velocity bounds do not narrow the reachable changes around the
// gap: the dip's velocities stay between v0 + a0^2 / 2J and vf - af^2 / 2J, both within the limits
// for a start and a target inside them.
struct Gap {
  double lo = 0.0;
  double hi = 0.0;
};
[[nodiscard]] Gap velocity_gap(double v0, double a0, double vf, double af, const AxisLimits& limits) noexcept;

class FarthestProfile {
 public:
  FarthestProfile() = default;  // unusable until one is constructed in its place (see the members)
  // Start (v0, a0) at position 0; end (vf, af); both inside `limits`.
  FarthestProfile(double v0, double a0, double vf, double af, const AxisLimits& limits) noexcept;

  // From this duration on, the farthest profile cruises at max_velocity, so the farthest position
  // grows linearly with slope max_velocity.
  [[nodiscard]] double cruise_from() const noexcept { return cruise_from_; }

  // The seven durations for duration T (>= the reach time). False only if no case fits, which means
  // T is below the reach time (by more than rounding). `rates`, if given, gets each duration's
  // derivative with respect to T within the case that fits (for position_and_slope).
  [[nodiscard]] bool durations(double T, SevenDurations& t, SevenDurations* rates = nullptr) const noexcept;
  // The end position of the farthest profile of duration T (NaN when durations() fails).
  [[nodiscard]] double position(double T) const noexcept;
  // The same, and the durations in `t` (unusable when NaN is returned); NaN too where durations
  // solved below the cruise end more than rounding away from (vf, af) (AxisProfile's arrival
  // tolerances): the arrival check of the profiles to a target at rest, which AxisProfile::prepare
  // does not integrate again.
  [[nodiscard]] double position(double T, SevenDurations& t) const noexcept;
  // The same and its derivative with respect to T, for a Newton step on the shortest duration
  // (NaN when durations() fails). The slope is that of the case of active bounds that fits T; where
  // the case changes it may jump, so its users keep a bracket.
  [[nodiscard]] double position_and_slope(double T, double& slope) const noexcept;
  // The lowest velocity along the profile with these durations.
  [[nodiscard]] double lowest_velocity_of(const SevenDurations& t) const noexcept;
  // With the end at rest (vf = af = 0): the shortest duration whose farthest position reaches
  // `target`, for a target between the position at the reach time and the one at the start of the
  // cruise. Solved over the peak velocity vp instead of the duration: below the cruise the farthest
  // profile rises from (v0, a0) to (vp, 0) and falls from there to rest, each half in closed form
  // (a trapezoid or a triangle of acceleration), so a Newton step costs a few multiplications where
  // one over the duration solved its case of active bounds first; where both halves hold their
  // acceleration bound (most roots) the position is quadratic in vp and the root comes in closed
  // form, without a step. NaN where that parametrisation does not hold the root or is
  // ill-conditioned there (a rise that starts by lowering the acceleration, a peak acceleration or
  // velocity near zero): the caller then searches the durations.
  [[nodiscard]] double duration_to_rest(double target) const noexcept;

 private:
  bool no_cruise(double T, SevenDurations& t, SevenDurations* rates) const noexcept;
  // The end position of the profile with these durations, whose cruise t[3] is zero (every profile
  // no_cruise() gives): its segment is not summed. With kArrival NaN where they end more than
  // rounding away from (vf, af).
  template <bool kArrival>
  [[nodiscard]] double position_of(const SevenDurations& t) const noexcept;
  // The same, and with kSlope its slope from `rates` (the durations' derivatives with respect to
  // T).
  template <bool kSlope, bool kArrival>
  [[nodiscard]] double position_of(const SevenDurations& t, const SevenDurations& rates,
                                   double& slope) const noexcept;
  [[nodiscard]] bool peak_within_velocity(double a1, double t2) const noexcept;

  // No default values: a default-constructed profile is only a place to construct one in (an axis
  // holds two, and zeroing them cost a rep stos per axis planned); the constructor sets every member.
  double v0_;
  double a0_;
  double vf_;
  double af_;
  AxisLimits lim_;
  SevenDurations cruise_shape_;  // with zero cruise
  double cruise_from_;
  // The end position at cruise_from_ (later ones are linear in T), summed from the cruise shape's
  // pieces in the constructor: it agrees with position_of() of that shape to rounding (2e-15
  // relative in random problems), not bit for bit.
  double cruise_position_;
  double inv_jerk_;  // 1 / jerk, jerk / 2 and / 6: the hot paths multiply, never divide
  double half_jerk_;
  double sixth_jerk_;
};

}  // namespace cellctl::planner

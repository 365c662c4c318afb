#pragma once
// One axis's planning problem: from any start state to a target state (position, velocity,
// acceleration) within its limits. Answers what synchronisation needs — the shortest duration and
// the blocked intervals (durations in between for which no profile exists) — and builds the profile
// for any feasible duration. Fixed-size, no allocation.
//
// The method (see farthest_profile.hpp): after the brake pre-profile (if the start is beyond the
// limits), a duration T is feasible when nearest(T) <= target <= farthest(T). Both functions are
// defined from the reach time on and linear once the extreme profile cruises. Each side's
// infeasible set is taken as at most an interval starting at the reach time (the shortest
// duration is its end) and one dip after it (a blocked interval; the random tests against an
// independent optimum found no second one). A target at rest has no dips (it can be reached at the
// reach time and held); otherwise dips are searched by sampling, crowded towards the reach time,
// and a golden-section refinement (the extremes are not convex near the reach time). Roots are found by
// regula falsi on T to the last bit, the shortest duration to a target at rest by Newton steps over
// the extreme's peak velocity (FarthestProfile::duration_to_rest; where that does not apply, over T on
// the extreme's position and slope, root_search.hpp); the optimum itself is an extreme profile, any other
// feasible duration a blend of the two, or to a target at rest of the extreme on its side and the
// fastest stop held at rest (see prepare()).
//
// A non-zero target acceleration can make its velocity and acceleration alone unreachable for a
// span of durations after the reach time (velocity_gap, in closed form): the search then runs
// before the gap (a window) and after it, and the gap lies in a blocked interval. The built
// profile is checked to arrive; a miss would be refused as unsupported_target rather than
// followed (none seen in millions of random problems). To a target at rest the pieces are not
// integrated again: the check is on the blend's position and on the extreme's solved durations
// ending at rest (FarthestProfile::position), and the profile's stated end is the target's state
// (see prepare()).
//
// To a target at rest, plan() leaves the search for the shortest duration to the first
// min_duration() call: time synchronisation asks only the axes that could set the common duration
// (reaches_by), about one per plan.

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "planner/axis_limits.hpp"
#include "planner/farthest_profile.hpp"
#include "planner/input.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// An open interval of durations [s]. A plain aggregate (Interval{} is (0, 0); no default member
// values): a trajectory's unused interval slots are then left unwritten (see Trajectory).
struct Interval {
  double lo;
  double hi;
  [[nodiscard]] bool contains(double t) const noexcept { return t > lo && t < hi; }
};

enum class AxisStatus : std::uint8_t {
  ok,
  target_outside_limits,  // target velocity/acceleration beyond the limits or bound to cross them
  unsupported_target,     // the built profile misses the target: a safety net (see above)
};

// Which bound a target state breaks and by how much (limit none: it keeps them all); the first in
// TargetLimit's order when it breaks several. Inline: every axis planned asks it.
[[nodiscard]] inline TargetExcess target_excess(const MotionState& target, const AxisLimits& l) noexcept {
  const double v = target.velocity;
  const double a = target.acceleration;
  const double ramp = a * a / (2.0 * l.jerk);  // velocity change while the acceleration ramps in
  if (v > l.max_velocity) return {TargetLimit::max_velocity, v - l.max_velocity};
  if (v < l.min_velocity) return {TargetLimit::min_velocity, l.min_velocity - v};
  if (a > l.max_acceleration) return {TargetLimit::max_acceleration, a - l.max_acceleration};
  if (a < l.min_acceleration) return {TargetLimit::min_acceleration, l.min_acceleration - a};
  // Arriving with a > 0 the velocity was lower just before: ramping a in from zero took `ramp` of
  // it, so v - ramp must be reachable (>= min_velocity); the mirror for a < 0.
  if (a > 0.0 && v - ramp < l.min_velocity)
    return {TargetLimit::min_velocity_on_arrival, l.min_velocity - (v - ramp)};
  if (a < 0.0 && v + ramp > l.max_velocity)
    return {TargetLimit::max_velocity_on_arrival, v + ramp - l.max_velocity};
  return {};
}

// Whether a profile that ends in `e` arrives in `target` up to rounding, its start (after any brake)
// `offset` short of the target's position: the safety net every built profile passes (a miss is
// unsupported_target).
[[nodiscard]] inline bool arrives_at(const MotionState& e, const MotionState& target, double offset,
                                     const AxisLimits& l) noexcept {
  const double scale = 1.0 + std::abs(offset);
  return std::abs(e.position - target.position) <= 1e-9 * scale &&
         std::abs(e.velocity - target.velocity) <= 1e-9 * (1.0 + l.max_velocity - l.min_velocity) &&
         std::abs(e.acceleration - target.acceleration) <=
             1e-9 * (1.0 + l.max_acceleration - l.min_acceleration);
}

// Used by one thread at a time: its const queries (min_duration(), reaches_by(), prepare()) fill
// caches of what plan() determined (mutable members), as a search or an evaluation is needed.
class AxisProfile {
 public:
  static constexpr std::size_t kMaxBlocked = 3;

  // Plans; on a status other than ok nothing else is meaningful, nor is anything before the first plan.
  AxisStatus plan(const MotionState& start, const MotionState& target, const AxisLimits& limits) noexcept;

  // The shortest duration, brake included [s]; +infinity when the search for it failed (no profile
  // is built at it: a plan whose common duration it would set is refused as unsupported_target; one
  // whose axes all reach their targets by a longer duration never asks it). To a target at rest it
  // is searched on the first call (see reaches_by); const, it writes a cache: see the class comment.
  [[nodiscard]] double min_duration() const noexcept {
    if (!min_known_) settle_min_duration();
    return min_duration_;
  }
  // Whether min_duration() is known without a search; and it if so, else NaN (without a branch).
  [[nodiscard]] bool min_duration_known() const noexcept { return min_known_; }
  [[nodiscard]] double min_duration_if_known() const noexcept {
    const std::array<double, 2> known{std::numeric_limits<double>::quiet_NaN(), min_duration_};
    return known[min_known_ ? 1 : 0];
  }
  // Whether the shortest duration is at most T, answered without searching for it. A synchronised
  // axis needs its own shortest duration only if it could be the longest: to a target at rest the
  // reachable positions only grow with the duration, so one evaluation at the common duration so far
  // tells whether this axis could raise it (searching cost about 200 instructions per axis, 490 where
  // it takes Newton steps; a time-synchronised plan of N axes to targets at rest now searches about
  // one). Exact where min_duration() is known; otherwise true when the extreme on the target's side
  // gets beyond the target at T by more than rounding (false says only that the search must decide).
  // To a target at rest (but from rest to rest with symmetric limits, built in closed form) it keeps
  // that evaluation for prepare() at T, known or not.
  [[nodiscard]] bool reaches_by(double T) const noexcept;
  // For an axis whose min_duration() is not known, a guess at it, for the order in which axes are
  // searched: the brake, the fastest stop, and the distance from its end to the target at the
  // velocity bound (a lower bound where the reachable positions grow at most that fast).
  [[nodiscard]] double min_duration_guess() const noexcept;
  [[nodiscard]] std::size_t blocked_count() const noexcept { return blocked_count_; }
  [[nodiscard]] const Interval& blocked(std::size_t i) const noexcept { return blocked_[i]; }
  // Whether a profile of total duration T exists (T >= min_duration, outside every blocked interval).
  [[nodiscard]] bool feasible(double T) const noexcept;
  // The brake then the profile ending in the target exactly at T (a feasible duration). False
  // (and `out` as it was) when the profile misses the target: an unsupported_target case.
  [[nodiscard]] bool build(double T, JerkProfile& out) const noexcept;
  // build() in two steps, so that a caller can check every axis before it writes one (a trajectory
  // then plans straight into the caller's, without a scratch copy): prepare() makes the pieces after
  // the brake (none empty) and checks where they end (integrating them as it goes, or to a target at
  // rest from its parts' ends), false when they miss the target; write() stores the brake and them.
  struct Built {
    std::array<JerkSegment, 2 * kFarthestJerkSigns.size() - 1> pieces;  // the first n are set
    std::size_t n;
    JerkProfile::Reached reached;
  };
  [[nodiscard]] bool prepare(double T, Built& built) const noexcept;
  void write(const Built& built, JerkProfile& out) const noexcept {
    out.assign_kept(brake_, built.pieces, built.n, built.reached);
  }
  [[nodiscard]] const JerkProfile& brake() const noexcept { return brake_; }

 private:
  // The set of durations (from the reach time on) for which one extreme falls short of the target.
  struct ShortSet {
    bool from_reach = false;  // [reach, end)
    double end = 0.0;
    bool dip = false;  // (dip_lo, dip_hi)
    double dip_lo = 0.0;
    double dip_hi = 0.0;
    bool gap = false;  // some duration searched had no extreme profile
  };
  // The short set of one side, searched from t0 (the reach time, or the end of a velocity gap), for a
  // target not at rest (plan() handles one at rest, which has no dip).
  [[nodiscard]] ShortSet short_set(const FarthestProfile& f, double target, double slope,
                                   double t0) const noexcept;
  // The first duration from t0 on at which f gets to `target`, given g0 = f.position(t0) - target < 0
  // and f's position never falling with more time (a target at rest); +infinity when some duration
  // searched had no extreme profile.
  [[nodiscard]] double shortest(const FarthestProfile& f, double target, double slope, double t0,
                                double g0) const noexcept;
  // The durations in [lo, hi] (between the reach time and a velocity gap) that reach the target,
  // taken as one window; false when neither the samples nor narrow_window between them find one.
  [[nodiscard]] bool feasible_window(double lo, double hi, Interval& window) const noexcept;
  // The window between two samples a and b, neither in it, that holds the target where it crosses
  // the middle of the reachable positions; false when it does not cross there.
  [[nodiscard]] bool narrow_window(double a, double b, Interval& window) const noexcept;
  // By how much the reachable positions at T (after the brake) hold the target: negative when
  // they miss it, -infinity when T has no extreme profile.
  [[nodiscard]] double margin(double T) const noexcept;

  // No default values (nor have the state's, limits' and stop's types): an axis is constructed for
  // every plan, and zeroing its members first cost 2 % of a moving plan. plan() sets every member
  // its queries read (even when it refuses: the shortest duration infinite), except those set on
  // demand: the extremes (extreme()), the kept evaluation (reaches_by(), read only at the duration
  // it was made for) and the blocked intervals past their count.
  JerkProfile brake_;
  MotionState main_start_;
  MotionState target_;
  double target_offset_;  // target position - main start position
  AxisLimits limits_;
  // Farthest in the positive direction (side 0), and in the mirrored frame (side 1: the nearest
  // profile), constructed on first use, or by plan() to a target at rest (the side it needs, see
  // plan()); each construction cost about 180 instructions. Mutable: a cache of what plan()
  // determined, built by the const queries.
  [[nodiscard]] const FarthestProfile& extreme(std::size_t side) const noexcept;
  // Not {}: that zeroed them (a rep stos) for every axis planned.
  mutable std::array<FarthestProfile, 2> extremes_;
  mutable std::array<bool, 2> constructed_;
  bool symmetric_;  // the second extreme is the first one mirrored: computed once
  int min_side_;    // the extreme whose profile is the shortest duration's (-1: a blend)
  double reach_;
  // To a target at rest: the fastest stop from the main start (the reach profile; none from rest),
  // which prepare() blends with the extreme on the target's side.
  Reach stop_;
  // The search for the shortest duration to a target at rest (plan() leaves it to min_duration()).
  void settle_min_duration() const noexcept;
  // Mutable: a cache of what plan() determined, searched by the const queries.
  mutable double min_duration_;  // brake included
  mutable bool min_known_;
  // reaches_by's evaluation of the extreme (its durations and position after `main` s from the main
  // start), which prepare() at the same duration takes instead of evaluating it again.
  mutable double checked_main_;
  mutable double checked_position_;
  mutable SevenDurations checked_;
  std::array<Interval, kMaxBlocked> blocked_;  // brake included
  std::size_t blocked_count_;
};

}  // namespace cellctl::planner

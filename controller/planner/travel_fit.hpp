#pragma once
// Keeping a time-synchronised axis in its travel when its profile at the common duration leaves it.
//
// Why: at a common duration T longer than its own shortest, an axis gets the blend of its two
// extreme profiles of duration T (axis_profile.hpp). Those extremes run far in both directions, and
// from a moving start the blend can reverse later than the axis must: it can leave the travel where
// the axis's own shortest motion stays inside (a start moving away from its target near the end of
// the travel, beside a longer move: refused before this existed). Every profile here is a jerk
// function from the same start state, so a mix of two of them, (1 - w) x + w y, is one too: it keeps
// every limit both keep (the bounds are convex), ends where both end, and its positions are the same
// mix of theirs. The lowest and highest position are convex in w: of the mixes of a profile inside
// the travel with the blend, the one nearest the blend that is still inside is found by bisection.
// For a target at rest, the axis's own shortest motion held at the target until T, if inside (else
// turn_first's motion, below), mixed with the blend then arrives with the others.

#include "planner/axis_limits.hpp"
#include "planner/input.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// How far `p` leaves [min_position, max_position] (<= 0: inside by that much), and which end.
[[nodiscard]] TravelExcess travel_excess(const JerkProfile& p, double min_position,
                                         double max_position) noexcept;

// (1 - w) x + w y: both from the same start state, of the same duration. Precondition: their
// switching times together fit in JerkProfile::kMaxSegments.
[[nodiscard]] JerkProfile mix(const JerkProfile& x, const JerkProfile& y, double w) noexcept;

// `inside` keeps the travel (or leaves it by less than `outside` does); both from the same start, of
// the same duration, ending in the same state. The mix nearest `outside` that leaves the travel by
// no more than `inside` does (not at all when `inside` keeps it).
[[nodiscard]] JerkProfile nearest_inside(const JerkProfile& inside, const JerkProfile& outside,
                                         double min_position, double max_position) noexcept;

// Where even the axis's own shortest motion leaves the travel, a slower one may not: the shortest
// motion to a target behind a moving start turns later than it could, to arrive sooner (1 m/s
// towards max_position, A 2, J 10: turning at once peaks 0.3467 on, the shortest motion to 0.345
// peaks at 0.3483). The fastest turn away from the end the motion leaves — full jerk against the
// velocity until it is zero, the acceleration held at its bound if reached first — reaches the
// least any motion can, and the shortest motion from there adds nothing towards that end (its
// velocity starts at zero, its acceleration away from it). `out`: that turn, then that motion.
// False when the start is not safe (is_safe) or is not moving towards that end, or no motion was
// planned from the turn's end.
[[nodiscard]] bool turn_first(const MotionState& start, const MotionState& target, const AxisLimits& limits,
                              bool towards_max, JerkProfile& out) noexcept;

}  // namespace cellctl::planner

#pragma once
// An independent numerical optimum for the planner's tests and benchmark. It shares no code with
// controller/planner.
//
// Feasibility at a fixed duration T: the end positions reachable at T with the target's end
// velocity and acceleration form an interval [near(T), far(T)] — the motions within the limits
// that end in (vf, af) at T are a convex set of jerk functions (every constraint is linear in the
// jerk) and the end position is linear in the jerk. T is feasible when near(T) <= D <= far(T), D
// the distance to the target. far(T) is found the slow, simple way, taking its motion to be
// bang-bang in jerk with the bounds held (the maximum principle): bisecting the end velocity over
// a one-parameter family of jerk sequences and integrating them; near(T) is far of the mirrored
// problem. That far and near are the true extremes is assumed, not proven here; oracle_test.cpp
// checks that no random motion within the limits ends beyond them.
//
// Minimality — that no duration below T is feasible — is proven, not sampled (the old check, 13
// evenly spread durations, passed claims that skipped a narrow feasible window: oracle_test.cpp).
// The proof inserts a cruise. A motion of duration t that passes a point where its acceleration is
// zero, at velocity w, becomes a motion of duration b > t with the same end state, ending w (b - t)
// further, by holding that velocity for b - t there (jerk and acceleration zero, w within the
// limits). So if such a motion reached D at t, D + w (b - t) would be reachable at b, hence lie in
// [near(b), far(b)]. A duration b with far(b) < D therefore proves every t in
// [b - (D - far(b)) / -w_lo, b] infeasible (every t < b when w_lo >= 0), near(b) > D likewise with
// (near(b) - D) / w_hi, and an end state (vf, af) not reachable at b at all (far and near both
// NaN; one alone proves nothing) proves every t < b infeasible. This needs far and near to be the
// true extremes, not that the reach is an interval.
// The bounds w_lo, w_hi hold for every motion of the problem that has such a point; the proof
// picks the point:
//   - a0 = 0 or af = 0: the start (w = v0) or the end (w = vf). A start or target at rest gives
//     w = 0: the feasible durations are [T_opt, inf) (wait at the start or the target) and one
//     infeasible duration proves all below it (2 feasibility tests per check);
//   - otherwise the first zero of the acceleration (the velocity has risen from v0 if a0 > 0: w >=
//     v0; fallen if a0 < 0: w <= v0) or the last (w <= vf if af > 0, w >= vf if af < 0), and w is
//     within [vmin, vmax] anyway. With a0 and af of opposite signs every motion has a zero;
//   - a0 and af of the same sign: a motion may keep that sign throughout and have no insertion
//     point. Its velocity is then monotone from v0 to vf, the jerk limit bends its start and end
//     (bounds in optimum_oracle.cpp), so D lies between two lines in t: an interval of t, the
//     "unresolved interval". Outside it the bounds above hold. Inside it one proof still covers
//     every motion: where (vf, af) is out of reach at b (a velocity gap), holding the acceleration
//     at its highest (lowest) point turns a motion at t into one at b ending faster (slower) by a
//     known rate, so the end velocities reachable at b (least and most effort, closed form) prove
//     a span below b out of reach too. What is left — (vf, af) reachable at b but D not, inside
//     the unresolved interval — falls back to a grid of 1/1024 of the unresolved interval below x.
// A claimed optimum T is checked by feasibility at T (1 + relative) and a scan down from
// x = T (1 - relative): at each b, feasible ends the check (T is not the optimum); otherwise b
// goes down by the longest step any problem proves (the best problem's, for several at once)
// until a proof reaches below 0.
//
// What this guarantees, given far and near: no duration in [0, x] is feasible, except that
//   - a step is at least eps / |w| long, eps = 1e-12 (1 + |D| + vmax b) in position (above the
//     oracle's rounding, far below what 1e-9 relative in duration means): where the reach at b
//     misses the target by less than eps, a window shorter than eps / |w| just below b may be
//     stepped over;
//   - inside a problem's unresolved interval (a0 and af nonzero of the same sign), at durations
//     where its end state is within reach but no motion with an insertion point reaches D, a
//     feasible window narrower than 1/1024 of that interval (below x) may be missed. Such windows
//     occur: in 10^6 random problems to an accelerating target, 3516 windows before a blocked
//     interval lay in an unresolved interval and 2260 were reached only through grid steps, as
//     narrow as 7.7e-6 x. A grid of x/1024 missed 56 of them, this one none (the narrowest seen in
//     3 10^5 problems was 2e-3 of its unresolved interval, twice the grid).
// A scan of more than 200 000 steps (the target grazing the reach from outside over a long span)
// gives up: the check then fails, with a note on stderr. Cost per check (feasibility tests, the
// issue's random problems at the planner's optimum): 2 for a start or target at rest, 8 moving to
// a moving target, 57 to an accelerating one — 42 of them grid points, in the 6 % of problems whose
// unresolved interval reaches below x (about 740 each). min_duration bisects on "a feasible
// duration in [0, x]", each decided by that scan.
//
// A start beyond the limits is braked first (brake_oracle.hpp: the earliest entry into the states
// from which the limits can be kept, found independently of the planner): feasible,
// min_duration and the confirmations count its brake, then prove the rest from the brake's end;
// every duration shorter than the brake is infeasible. reach() takes a start inside the limits.

#include <vector>

namespace cellctl::planner::oracle {

struct Limits {
  double vmax, vmin, amax, amin, jerk;
};

struct Problem {
  double p0, v0, a0;  // start: anywhere (beyond the limits: braked first, see above)
  double pf, vf, af;  // target, likewise
  Limits limits;
};

// The end positions reachable at T relative to the start, with the target's end velocity and
// acceleration: [near, far]; NaN when that end state cannot be reached at T.
struct Reach {
  double near, far;
  [[nodiscard]] bool defined() const;
};
[[nodiscard]] Reach reach(const Problem& p, double T);

// Whether some motion of exactly duration T solves the problem within the limits.
[[nodiscard]] bool feasible(const Problem& p, double T);

// The shortest feasible duration, searched on [0, upper]: bisection on "some duration in [0, x]
// is feasible", each decided by the proven scan; +infinity when none is found there.
[[nodiscard]] double min_duration(const Problem& p, double upper);

// Whether T is the shortest duration within `relative`: feasible at T (1 + relative), and none
// feasible in [0, T (1 - relative)] by the proven scan (above).
[[nodiscard]] bool confirms_min_duration(const Problem& p, double T, double relative);
// The same for the shortest duration feasible for every problem at once.
[[nodiscard]] bool confirms_min_common_duration(const std::vector<Problem>& problems, double T,
                                                double relative);

// The shortest duration feasible for every problem at once (time synchronisation).
[[nodiscard]] double min_common_duration(const std::vector<Problem>& problems, double upper);

}  // namespace cellctl::planner::oracle

#pragma once
// An independent numerical optimum for the planner's tests and benchmark. It shares no code with
// controller/planner: it only relies on the facts that the end positions reachable at a fixed
// duration with a fixed end velocity and acceleration form an interval, and that its ends are met
// by bang-bang jerk with the bounds held (the maximum principle). Everything else is done the slow,
// simple way: for a duration T the farthest end is found by bisecting the end velocity over a
// one-parameter family of jerk sequences and integrating them; the shortest duration by scanning T
// and bisecting the first feasible one to the last bit. Slow (tens of microseconds), obviously right.

#include <vector>

namespace cellctl::planner::oracle {

struct Limits {
  double vmax, vmin, amax, amin, jerk;
};

struct Problem {
  double p0, v0, a0;  // start, inside the limits and able to stay inside them
  double pf, vf, af;  // target, likewise
  Limits limits;
};

// Whether some motion of exactly duration T solves the problem within the limits.
[[nodiscard]] bool feasible(const Problem& p, double T);

// The shortest feasible duration, searched on [0, upper]; +infinity when none is found there.
[[nodiscard]] double min_duration(const Problem& p, double upper);

// Whether T is the shortest duration within `relative`: feasible just above T, and infeasible at
// T (1 - relative) and at evenly spread durations below it. (The check min_duration makes, without
// the bisection: fast enough for the test suite's hundred thousand problems.)
[[nodiscard]] bool confirms_min_duration(const Problem& p, double T, double relative);
// The same for the shortest duration feasible for every problem at once.
[[nodiscard]] bool confirms_min_common_duration(const std::vector<Problem>& problems, double T,
                                                double relative);

// The shortest duration feasible for every problem at once (time synchronisation).
[[nodiscard]] double min_common_duration(const std::vector<Problem>& problems, double upper);

}  // namespace cellctl::planner::oracle

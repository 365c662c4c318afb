#pragma once
// Seeded random planning problems for the planner's tests and benchmark, drawn as issue 11 says:
// per axis max velocity U(0.5, 5), max acceleration U(1, 20), max jerk U(10, 200), positions
// U(-5, 5); the target at rest unless asked otherwise. The limits are tight as often as these
// draws make them: max velocity below max acceleration^2 / max jerk (a ramp up and down of max
// acceleration changes the velocity by more than the limit) in 28 % of them, the whole velocity
// range narrower than one ramp (2 max velocity < max acceleration^2 / 2 max jerk) in 6 %.
// The start (issue 23: as the cell meets it, never re-drawn):
// - moving: velocity and acceleration anywhere within their bounds, so that the starts whose
//   speed must overshoot a limit (bound to cross it whatever the jerk does) come in the
//   proportion this draw gives them (8 % of the axes) — what a new target while moving meets;
// - beyond_limits: the same from bounds twice as wide (the limits lowered while moving, a speed
//   override or an unhold from a brake at another ramp): acceleration and velocity beyond them;
// - within: moving and able to stay within the limits (re-drawn until it can), the start that
//   FarthestProfile and oracle::reach take: for their own tests only.

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "planner/input.hpp"
#include "planner/optimum_oracle.hpp"

namespace cellctl::planner::testing {

enum class Start { at_rest, moving, beyond_limits, within };
// The target state: at rest; moving (a velocity, zero acceleration); accelerating (both).
enum class Target { at_rest, moving, accelerating };

inline bool stays_within(double v, double a, const oracle::Limits& l) {
  const double ramp = a * a / (2.0 * l.jerk);
  return (a <= 0.0 || v + ramp <= l.vmax) && (a >= 0.0 || v - ramp >= l.vmin);
}

inline oracle::Problem random_problem(std::mt19937_64& rng, Start start, Target target = Target::at_rest) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto U = [&](double lo, double hi) { return lo + (hi - lo) * u01(rng); };
  oracle::Problem p{};
  const double v = U(0.5, 5.0);
  const double a = U(1.0, 20.0);
  p.limits = oracle::Limits{v, -v, a, -a, U(10.0, 200.0)};
  p.p0 = U(-5.0, 5.0);
  p.pf = U(-5.0, 5.0);
  if (start == Start::moving) {
    p.v0 = U(-v, v);
    p.a0 = U(-a, a);
  }
  if (start == Start::beyond_limits) {
    p.v0 = U(-2.0 * v, 2.0 * v);
    p.a0 = U(-2.0 * a, 2.0 * a);
  }
  if (start == Start::within) {
    do {
      p.v0 = U(-v, v);
      p.a0 = U(-a, a);
    } while (!stays_within(p.v0, p.a0, p.limits));
  }
  if (target == Target::moving) p.vf = U(-v, v);
  if (target == Target::accelerating) {
    do {
      p.vf = U(-v, v);
      p.af = U(-a, a);
    } while (!stays_within(p.vf, -p.af, p.limits));
  }
  return p;
}

// The problem count: the environment variable CELLCTL_PLANNER_PROBLEMS if set, else `fallback`.
inline long problem_count(long fallback) {
  const char* env = std::getenv("CELLCTL_PLANNER_PROBLEMS");
  return env != nullptr ? std::strtol(env, nullptr, 10) : fallback;
}

// The seed: CELLCTL_PLANNER_SEED if set, else `fallback` (printed by the tests, so a failure can be
// replayed).
inline std::uint64_t problem_seed(std::uint64_t fallback) {
  const char* env = std::getenv("CELLCTL_PLANNER_SEED");
  return env != nullptr ? std::strtoull(env, nullptr, 10) : fallback;
}

// The planner's input for one problem per axis (symmetric limits, as drawn).
template <int N>
Input<N> input_of(const std::vector<oracle::Problem>& axes) {
  Input<N> in;
  for (int i = 0; i < N; ++i) {
    const oracle::Problem& p = axes[static_cast<std::size_t>(i)];
    in.current_position[i] = p.p0;
    in.current_velocity[i] = p.v0;
    in.current_acceleration[i] = p.a0;
    in.target_position[i] = p.pf;
    in.target_velocity[i] = p.vf;
    in.target_acceleration[i] = p.af;
    in.max_velocity[i] = p.limits.vmax;
    in.max_acceleration[i] = p.limits.amax;
    in.max_jerk[i] = p.limits.jerk;
  }
  return in;
}

}  // namespace cellctl::planner::testing

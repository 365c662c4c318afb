// The brake oracle's claim, checked without it: no jerk-limited motion from a start beyond the
// limits enters the safe states sooner than the brake it finds.

#include "planner/brake_oracle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "planner/random_problems.hpp"

namespace cellctl::planner {
namespace {

// Random motions from the start: bang-bang in jerk with up to three switches at random times (the
// shape of every time-optimal motion of this kind) and, for one in four, a random jerk level on
// each piece. An acceleration beyond its bound comes back at full jerk and is then kept within it
// (the motions the brake is the shortest of). Returns the earliest time at which a state at the end
// of one of `steps` equal steps up to `horizon` is in S (+infinity if none).
double earliest_entry(const oracle::Problem& p, double horizon, std::mt19937_64& rng) {
  constexpr int kSteps = 4000;
  const oracle::Limits& l = p.limits;
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::array<double, 4> switch_at{};
  std::array<double, 4> level{};
  const bool levels = u01(rng) < 0.25;
  const double first = u01(rng) < 0.5 ? 1.0 : -1.0;
  for (std::size_t k = 0; k < switch_at.size(); ++k) {
    switch_at[k] = horizon * u01(rng);
    level[k] = (k % 2 == 0 ? first : -first) * (levels ? u01(rng) : 1.0);
  }
  std::sort(switch_at.begin(), switch_at.end());
  const double dt = horizon / kSteps;
  double v = p.v0;
  double a = p.a0;
  for (int s = 1; s <= kSteps; ++s) {
    const double t = s * dt;
    std::size_t piece = 0;
    while (piece + 1 < switch_at.size() && t > switch_at[piece + 1]) ++piece;
    double jerk = (t < switch_at[0] ? level[0] : level[piece]) * l.jerk;
    if (a > l.amax) jerk = -l.jerk;
    if (a < l.amin) jerk = l.jerk;
    if (a <= l.amax && a + jerk * dt > l.amax) jerk = (l.amax - a) / dt;
    if (a >= l.amin && a + jerk * dt < l.amin) jerk = (l.amin - a) / dt;
    v += dt * (a + dt * jerk / 2.0);
    a += dt * jerk;
    if (oracle::in_safe_set(v, a, l)) return t;
  }
  return std::numeric_limits<double>::infinity();
}

TEST(BrakeOracle, NoRandomMotionEntersTheSafeStatesSooner) {
  std::mt19937_64 rng(testing::problem_seed(2300));
  long braked = 0;
  for (int n = 0; n < 300 && !::testing::Test::HasFailure(); ++n) {
    const oracle::Problem p = testing::random_problem(rng, testing::Start::beyond_limits);
    const double brake = oracle::braked(p).delay;
    if (brake == 0.0) continue;
    ++braked;
    // Up to 0.1 % before the brake's end: S is touched tangentially as a rule, so closer to it a
    // motion that only grazes S within rounding would count.
    const double horizon = brake * (1.0 - 1e-3);
    for (int m = 0; m < 200; ++m) {
      const double entry = earliest_entry(p, horizon, rng);
      ASSERT_FALSE(entry <= horizon) << "problem " << n << ": v0 " << p.v0 << " a0 " << p.a0 << " vmax "
                                     << p.limits.vmax << " amax " << p.limits.amax << " jerk "
                                     << p.limits.jerk << ": a motion enters S at " << entry
                                     << " s, the brake takes " << brake << " s";
    }
  }
  EXPECT_GT(braked, 100);
}

}  // namespace
}  // namespace cellctl::planner

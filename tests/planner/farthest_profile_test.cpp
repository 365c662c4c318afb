// The farthest profile's slope (d position / d T), which the Newton search for the shortest
// duration relies on: against finite differences on random problems, every case of active bounds.
// The reach time's distance, which stands for both extremes there. The shortest duration to a
// target at rest solved over the peak velocity (duration_to_rest), against the duration that made
// the target. The stop to rest, the same as the reach to a target at rest, bit for bit.

#include "planner/farthest_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "planner/random_problems.hpp"

namespace cellctl::planner {
namespace {

TEST(FarthestProfile, SlopeMatchesFiniteDifferences) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 3000; ++n) {
    const oracle::Problem p = testing::random_problem(
        rng, testing::Start::within, n % 2 == 0 ? testing::Target::at_rest : testing::Target::moving);
    const AxisLimits l{p.limits.vmax, p.limits.vmin, p.limits.amax, p.limits.amin, p.limits.jerk};
    const FarthestProfile f(p.v0, p.a0, p.vf, p.af, l);
    const double reach = planner::reach(p.v0, p.a0, p.vf, p.af, l).time;
    if (!(f.cruise_from() > reach)) continue;
    const double T = reach + (f.cruise_from() - reach) * (0.01 + 0.98 * u01(rng));
    double slope = 0.0;
    const double at = f.position_and_slope(T, slope);
    ASSERT_EQ(at, f.position(T)) << n;
    // Where the case of active bounds changes the slope may jump: it must then match one side.
    const double h = 1e-6 * T;
    const double left = (f.position(T) - f.position(T - h)) / h;
    const double right = (f.position(T + h) - f.position(T)) / h;
    const double tol = 1e-3 * (std::abs(left) + std::abs(right)) + 1e-6;
    EXPECT_TRUE(std::abs(slope - left) <= tol || std::abs(slope - right) <= tol)
        << "problem " << n << " T " << T << ": slope " << slope << ", differences " << left << " " << right;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(FarthestProfile, BothExtremesAtTheReachTimeAreTheFastestProfile) {
  std::mt19937_64 rng(8);
  for (int n = 0; n < 20000; ++n) {
    const auto target = static_cast<testing::Target>(n % 3);
    const oracle::Problem p = testing::random_problem(rng, testing::Start::within, target);
    const AxisLimits l{p.limits.vmax, p.limits.vmin, p.limits.amax, p.limits.amin, p.limits.jerk};
    const Reach r = reach(p.v0, p.a0, p.vf, p.af, l);
    ASSERT_TRUE(std::isfinite(r.time)) << n;
    const double far = FarthestProfile(p.v0, p.a0, p.vf, p.af, l).position(r.time);
    const double near = -FarthestProfile(-p.v0, -p.a0, -p.vf, -p.af, l.mirrored()).position(r.time);
    EXPECT_NEAR(r.position, far, 1e-10 * (1.0 + std::abs(far))) << n;
    EXPECT_NEAR(r.position, near, 1e-10 * (1.0 + std::abs(near))) << n;
  }
}

// stop_to_rest() is reach() with the target's zeros folded in by the compiler, and only the rise
// that can stop computed away from the curve where ramping the acceleration out stops the axis:
// every field the same bits (a fold that changed a value, e.g. of x + 0.0 where x may be -0.0, or a
// rise skipped that reach() would have taken, would show here). The curve offsets find a threshold
// for the one-rise path 110 times below the one derived (1e-13 s^2 fails, 1e-12 passes, 1.1e-11 is
// used), so a derivation wrong by that much fails here.
TEST(FarthestProfile, TheStopToRestIsTheReachToRestBitForBit) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (int n = 0; n < 20000; ++n) {
    const oracle::Problem p = testing::random_problem(rng, testing::Start::within);
    const double slower = n % 2 == 0 ? 1.0 : 0.3 + 0.7 * u01(rng);
    const AxisLimits l{p.limits.vmax, slower * p.limits.vmin, p.limits.amax, slower * p.limits.amin,
                       p.limits.jerk};
    // At rest, on a bound, and signed zeros too: the edges where a fold could differ. Then on and
    // about the curve v = -a |a| / 2J, from an ulp to 1e-8 relative off it, where the two rises are
    // close to a tie (a third of them with a tiny acceleration): where the one skipped could be taken.
    const double curve_a = n % 3 == 0 ? 1e-13 * p.a0 : p.a0;
    const double curve_v = -curve_a * std::abs(curve_a) / (2.0 * l.jerk);
    const double off = std::array<double, 8>{
        0.0, 1e-15, 1e-12, 3e-12, 1e-11, 3e-11, 1e-10, 1e-8}[static_cast<std::size_t>(n % 8)];
    const std::array<double, 8> v{p.v0,
                                  0.0,
                                  -0.0,
                                  n % 2 == 0 ? l.max_velocity : l.min_velocity,
                                  curve_v,
                                  std::nextafter(curve_v, n % 2 == 0 ? 1.0 : -1.0),
                                  curve_v * (1.0 + off),
                                  curve_v * (1.0 - off)};
    const std::array<double, 8> a{
        p.a0,    0.0,     -0.0,    n % 2 == 0 ? l.min_acceleration : l.max_acceleration,
        curve_a, curve_a, curve_a, curve_a};
    for (std::size_t k = 0; k < v.size(); ++k) {
      const double a0 = std::clamp(a[k], l.min_acceleration, l.max_acceleration);
      const Reach r = reach(v[k], a0, 0.0, 0.0, l);
      const Reach s = stop_to_rest(v[k], a0, l);
      ASSERT_TRUE(same(r.time, s.time) &&
                  (same(r.position, s.position) || (std::isnan(r.position) && std::isnan(s.position))) &&
                  same(r.direction, s.direction) && same(r.ramp_in, s.ramp_in) && same(r.hold, s.hold) &&
                  same(r.ramp_out, s.ramp_out))
          << "problem " << n << " case " << k << ": v " << v[k] << " a " << a0;
    }
  }
}

TEST(FarthestProfile, TheDurationToRestIsTheOneThatGetsToTheTarget) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int checked = 0;
  int solved = 0;
  for (int n = 0; n < 20000; ++n) {
    const oracle::Problem p = testing::random_problem(rng, testing::Start::within);
    // Asymmetric limits half the time: the nearest extreme is the farthest one of the mirrored frame.
    const double slower = n % 2 == 0 ? 1.0 : 0.3 + 0.7 * u01(rng);
    const AxisLimits l{p.limits.vmax, slower * p.limits.vmin, p.limits.amax, slower * p.limits.amin,
                       p.limits.jerk};
    if (!(p.v0 >= l.min_velocity && p.a0 >= l.min_acceleration)) continue;
    const FarthestProfile f(p.v0, p.a0, 0.0, 0.0, l);
    const double reach = planner::reach(p.v0, p.a0, 0.0, 0.0, l).time;
    if (!(f.cruise_from() > reach)) continue;
    // A target the farthest profile of duration `made` gets to exactly, before the cruise.
    const double made = reach + (f.cruise_from() - reach) * (0.001 + 0.998 * u01(rng));
    const double target = f.position(made);
    ++checked;
    const double T = f.duration_to_rest(target);
    if (std::isnan(T)) continue;  // not in its domain: the caller searches over durations
    ++solved;
    // To rounding (2e-13 and 1e-14 at most in 200 000 of these): build() takes the extreme of the
    // shortest duration as it is only within 1e-13 of the target (a blend otherwise, slower). Without
    // the correction of the duration for the rounding of vp, 9.8e-14 of position here.
    EXPECT_NEAR(T, made, 1e-12 * made) << "problem " << n;
    EXPECT_NEAR(f.position(T), target, 3e-14 * (1.0 + std::abs(target))) << "problem " << n;
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(solved, 9 * checked / 10);  // the fast path must be the rule, or it is no speed-up
}

}  // namespace
}  // namespace cellctl::planner

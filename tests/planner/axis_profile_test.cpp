#include "planner/axis_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "planner/brake_oracle.hpp"
#include "planner/optimum_oracle.hpp"
#include "planner/random_problems.hpp"
#include "planner/segments_end.hpp"

namespace cellctl::planner {
namespace {

using testing::Start;
using testing::Target;

AxisLimits limits_of(const oracle::Problem& p) {
  return AxisLimits{p.limits.vmax, p.limits.vmin, p.limits.amax, p.limits.amin, p.limits.jerk};
}

// Checks a built profile: exact end state, every segment within the limits (velocity extrema
// inside segments included), from the end of the brake on.
void expect_within(const JerkProfile& profile, const MotionState& target, const AxisLimits& l, double brake,
                   const std::string& what) {
  MotionState s = profile.start();
  double t = 0.0;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const JerkSegment seg = profile.segment(i);
    EXPECT_LE(std::abs(seg.jerk), l.jerk * (1 + 1e-12)) << what;
    const MotionState next = integrate(s, seg.jerk, seg.duration);
    if (t >= brake - 1e-12) {
      EXPECT_LE(next.acceleration, l.max_acceleration + 1e-9) << what << " segment " << i;
      EXPECT_GE(next.acceleration, l.min_acceleration - 1e-9) << what << " segment " << i;
      double vmax = std::max(s.velocity, next.velocity);
      double vmin = std::min(s.velocity, next.velocity);
      if (seg.jerk != 0.0) {
        const double tz = -s.acceleration / seg.jerk;
        if (tz > 0.0 && tz < seg.duration) {
          const double vz = integrate(s, seg.jerk, tz).velocity;
          vmax = std::max(vmax, vz);
          vmin = std::min(vmin, vz);
        }
      }
      EXPECT_LE(vmax, l.max_velocity + 1e-9) << what << " segment " << i;
      EXPECT_GE(vmin, l.min_velocity - 1e-9) << what << " segment " << i;
    }
    s = next;
    t += seg.duration;
  }
  // Where the segments lead (the end the profile states may be the target's, see segments_end.hpp).
  EXPECT_NEAR(s.position, target.position, 1e-8) << what;
  EXPECT_NEAR(s.velocity, target.velocity, 1e-8) << what;
  EXPECT_NEAR(s.acceleration, target.acceleration, 1e-8) << what;
}

// The problem from the end of the planner's brake on (the oracle then proves the rest).
oracle::Problem after_brake(const oracle::Problem& p, const JerkProfile& brake) {
  oracle::Problem q = p;
  q.p0 = brake.end().position;
  q.v0 = brake.end().velocity;
  q.a0 = brake.end().acceleration;
  return q;
}

// The planner's brake is the oracle's (brake_oracle.hpp): as long, ending in the same state.
void expect_oracle_brake(const oracle::Problem& p, const JerkProfile& brake, const std::string& what) {
  const oracle::Braked b = oracle::braked(p);
  EXPECT_NEAR(brake.duration(), b.delay, 1e-9 * b.delay + 1e-12) << what << ": the brake";
  const double scale = 1.0 + p.limits.vmax + p.limits.amax;
  EXPECT_NEAR(brake.end().velocity, b.problem.v0, 1e-7 * scale) << what << ": the brake's end";
  // The oracle finds the end acceleration only as well as the velocity it changes: near a held
  // bound, ending x below it costs x^2 / 2J of velocity, so x up to sqrt(2J 1e-13 scale) is lost in
  // rounding (seed 13 problem 15522 of the starts beyond the limits: 4.8e-7 at J 161).
  const double flat = std::sqrt(2.0 * p.limits.jerk * 1e-13 * scale);
  EXPECT_NEAR(brake.end().acceleration, b.problem.a0, 1e-7 * scale + flat) << what << ": the brake's end";
  EXPECT_NEAR(brake.end().position, b.problem.p0, 1e-7 * (scale + std::abs(p.p0)))
      << what << ": the brake's end";
}

// Returns false when the plan was refused (counted: every random test expects none, the oracle
// plans every problem drawn).
bool check_problem(const oracle::Problem& p, std::mt19937_64& rng, const std::string& what) {
  AxisProfile axis;
  const AxisLimits l = limits_of(p);
  const MotionState target{p.pf, p.vf, p.af};
  const AxisStatus status = axis.plan({p.p0, p.v0, p.a0}, target, l);
  if (status != AxisStatus::ok) return false;
  expect_oracle_brake(p, axis.brake(), what);
  const double brake = axis.brake().duration();
  const oracle::Problem q = after_brake(p, axis.brake());
  const double T = axis.min_duration();
  EXPECT_TRUE(oracle::confirms_min_duration(q, T - brake, 1e-9))
      << what << ": planned " << T - brake << " s after the brake, the independent optimum is "
      << oracle::min_duration(q, 1.01 * T + 1e-9);
  JerkProfile profile;
  EXPECT_TRUE(axis.build(T, profile)) << what;
  EXPECT_NEAR(profile.duration(), T, 1e-9 * T + 1e-12) << what;
  expect_within(profile, target, l, brake, what);
  // Every blocked interval: infeasible inside by the oracle, feasible at its end.
  for (std::size_t b = 0; b < axis.blocked_count(); ++b) {
    const Interval& in = axis.blocked(b);
    EXPECT_FALSE(oracle::feasible(q, 0.5 * (in.lo + in.hi) - brake))
        << what << " blocked " << in.lo << ".." << in.hi;
    EXPECT_TRUE(oracle::feasible(q, in.hi * (1 + 1e-12) - brake)) << what << " after blocked " << in.hi;
    EXPECT_TRUE(oracle::feasible(q, in.lo * (1 - 1e-12) - brake)) << what << " before blocked " << in.lo;
  }
  // A longer feasible duration (as time synchronisation asks for) ends there exactly too.
  std::uniform_real_distribution<double> stretch(1.0, 3.0);
  double longer = T * stretch(rng) + 1e-3;
  for (std::size_t b = 0; b < axis.blocked_count(); ++b) {
    if (axis.blocked(b).contains(longer)) longer = axis.blocked(b).hi;
  }
  EXPECT_TRUE(axis.feasible(longer)) << what;
  if (!axis.build(longer, profile)) {
    ADD_FAILURE() << what << ": no profile for the feasible duration " << longer;
    return true;
  }
  EXPECT_NEAR(profile.duration(), longer, 1e-9 * longer) << what;
  expect_within(profile, target, l, brake, what + " stretched");
  return true;
}

std::string describe(const oracle::Problem& p, long i, std::uint64_t seed) {
  char buf[400];
  std::snprintf(
      buf, sizeof buf,
      "problem %ld (seed %llu): p0 %.17g v0 %.17g a0 %.17g -> pf %.17g vf %.17g af %.17g; vmax %.17g "
      "amax %.17g jerk %.17g",
      i, static_cast<unsigned long long>(seed), p.p0, p.v0, p.a0, p.pf, p.vf, p.af, p.limits.vmax,
      p.limits.amax, p.limits.jerk);
  return buf;
}

// Each random test runs in kParts parts, ctest cases of their own: the parts check consecutive
// blocks of one seeded sequence of problems (a problem's number and what it is do not depend on the
// parts), so two cores share a test and no part comes near ctest's time limit under ASan on a loaded
// machine (two whole tests took 241 s together there, and 300 s each, ctest's limit, in the
// dev tree at -O0 under load).
constexpr int kParts = 4;

// Returns how many plans of part `part` were refused. A refusal is not a failure by itself, so that a
// run counts them all; the tests expect none (the oracle plans every problem drawn: no start is
// beyond recovery, no target beyond the limits, the travel unbounded).
long run_random(Start start, Target target, long fallback_count, std::uint64_t fallback_seed, int part) {
  const long count = testing::problem_count(fallback_count);
  const std::uint64_t seed = testing::problem_seed(fallback_seed);
  const long first = count * part / kParts;
  const long end = count * (part + 1) / kParts;
  std::mt19937_64 rng(seed);
  long refused = 0;
  long braked = 0;
  for (long i = 0; i < end; ++i) {
    const oracle::Problem p = testing::random_problem(rng, start, target);
    if (i < first) continue;  // another part's: drawn, so that this part's are the same problems
    braked += oracle::braked(p).delay > 0.0 ? 1 : 0;
    // The stretched duration from a generator of the problem's own: the same whatever part runs it
    // and whatever was refused before it.
    std::mt19937_64 stretches(seed + 1000 + static_cast<std::uint64_t>(i));
    if (!check_problem(p, stretches, describe(p, i, seed))) {
      if (refused == 0) std::printf("first refusal: %s\n", describe(p, i, seed).c_str());
      ++refused;
    }
    if (::testing::Test::HasFailure()) break;
    // Progress for long runs (CELLCTL_PLANNER_PROBLEMS in the millions).
    if ((i + 1 - first) % 250000 == 0) {
      std::printf("  %ld problems passed so far\n", i + 1 - first);
      std::fflush(stdout);
    }
  }
  std::printf("problems %ld to %ld of %ld (seed %llu): %ld braked first, %ld refused\n", first, end - 1,
              count, static_cast<unsigned long long>(seed), braked, refused);
  return refused;
}

// The fastest stop from (v0, a0) held at rest until T, as Reach describes it, from position 0.
JerkProfile stop_held(double v0, double a0, const Reach& stop, double T, const AxisLimits& l) {
  JerkProfile held(MotionState{0.0, v0, a0});
  const double jerk = stop.direction * l.jerk;
  const std::array<JerkSegment, 4> pieces{
      {{jerk, stop.ramp_in}, {0.0, stop.hold}, {-jerk, stop.ramp_out}, {0.0, T - stop.time}}};
  held.append(pieces.data(), pieces.size());
  return held;
}

// To a target at rest, a duration longer than the shortest is the blend of the extreme profile on
// the target's side with the fastest stop held at rest (AxisProfile::prepare): both made here from
// their definitions, the share from where they end, and every piece of the built profile has their
// blended jerk. It keeps the limits, arrives, and is not refused.
TEST(AxisProfileBlend, ALongerDurationToATargetAtRestBlendsTheExtremeWithTheFastestStop) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> stretch(1.0, 3.0);
  int blended = 0;  // with a share strictly between 0 and 1
  for (int n = 0; n < 3000; ++n) {
    const oracle::Problem p = testing::random_problem(rng, Start::moving, Target::at_rest);
    const std::string what = describe(p, n, 23);
    const AxisLimits l = limits_of(p);
    const MotionState target{p.pf, 0.0, 0.0};
    AxisProfile axis;
    ASSERT_EQ(axis.plan({p.p0, p.v0, p.a0}, target, l), AxisStatus::ok) << what;
    if (axis.brake().duration() > 0.0) continue;  // the same from the brake's end: not re-derived here
    const double T = axis.min_duration() * stretch(rng) + 1e-3;
    JerkProfile built;
    ASSERT_TRUE(axis.build(T, built)) << what << ": refused at " << T;
    expect_within(built, target, l, 0.0, what);
    // The stop: the fastest change to rest, then held.
    const Reach stop = reach(p.v0, p.a0, 0.0, 0.0, l);
    const JerkProfile held = stop_held(p.v0, p.a0, stop, T, l);
    const MotionState stopped = held.at(stop.time);
    EXPECT_NEAR(stopped.position, stop.position, 1e-9 * (1.0 + std::abs(stop.position))) << what;
    EXPECT_NEAR(stopped.velocity, 0.0, 1e-9 * (1.0 + p.limits.vmax)) << what;
    EXPECT_NEAR(stopped.acceleration, 0.0, 1e-9 * (1.0 + p.limits.amax)) << what;
    // The extreme on the target's side (beyond the stop's end).
    const double offset = p.pf - p.p0;
    const double sign = offset > stop.position ? 1.0 : -1.0;
    const FarthestProfile extreme = sign > 0.0 ? FarthestProfile(p.v0, p.a0, 0.0, 0.0, l)
                                               : FarthestProfile(-p.v0, -p.a0, 0.0, 0.0, l.mirrored());
    SevenDurations d{};
    const double reached = sign * extreme.position(T, d);
    ASSERT_FALSE(std::isnan(reached)) << what;
    JerkProfile far(MotionState{0.0, p.v0, p.a0});
    for (std::size_t i = 0; i < d.size(); ++i) far.append({sign * kFarthestJerkSigns[i] * l.jerk, d[i]});
    const double width = reached - stop.position;
    const double share = width != 0.0 ? std::clamp((offset - stop.position) / width, 0.0, 1.0) : 0.0;
    blended += share > 0.0 && share < 1.0 ? 1 : 0;
    double t = 0.0;
    for (std::size_t i = 0; i < built.size(); ++i) {
      const JerkSegment& seg = built.segment(i);
      const double mid = t + seg.duration / 2.0;
      t += seg.duration;
      if (seg.duration < 1e-9) continue;  // its middle may lie on the other side of a rounded switch
      EXPECT_NEAR(seg.jerk, share * far.jerk_at(mid) + (1.0 - share) * held.jerk_at(mid), 1e-9 * l.jerk)
          << what << " at " << T << " s, segment " << i << " (share " << share << ")";
    }
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(blended, 2000);
}

// A target where the fastest stop ends: the blend's share of the extreme is 0, the stop then a hold.
TEST(AxisProfileBlend, ATargetWhereTheFastestStopEndsIsThatStopHeld) {
  const AxisLimits l = AxisLimits::symmetric(1.0, 2.0, 10.0);
  const MotionState start{0.0, 0.6, 1.5};  // at 0: the target's offset is the stop's distance exactly
  const Reach stop = reach(start.velocity, start.acceleration, 0.0, 0.0, l);
  const MotionState target{stop.position, 0.0, 0.0};
  AxisProfile axis;
  ASSERT_EQ(axis.plan(start, target, l), AxisStatus::ok);
  EXPECT_EQ(axis.min_duration(), stop.time);
  const double T = stop.time + 0.5;
  JerkProfile built;
  ASSERT_TRUE(axis.build(T, built));
  expect_within(built, target, l, 0.0, "the stop held");
  const JerkProfile held = stop_held(start.velocity, start.acceleration, stop, T, l);
  for (int k = 0; k <= 100; ++k) {
    const double t = T * k / 100.0;
    EXPECT_NEAR(built.at(t).position, held.at(t).position, 1e-12) << t;
    EXPECT_NEAR(built.at(t).velocity, held.at(t).velocity, 1e-12) << t;
  }
}

// A synchronised axis asks reaches_by() whether its shortest duration is at most the common one
// before it searches for it (Trajectory::longest_min_duration): the answer must be the search's,
// from moving starts (braked ones too) to targets at rest and to moving ones (whose shortest
// duration plan() knows). And the evaluation it keeps for build() must give the same profile, bit
// for bit, as one built without it, at that duration and at another.
TEST(AxisProfileReachesBy, AnswersAsTheSearchForTheShortestDuration) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> stretch(1.0, 3.0);
  int unknown = 0;  // plans that left the search to min_duration()
  for (int n = 0; n < 4000; ++n) {
    const Target kind = n % 4 == 0 ? Target::moving : Target::at_rest;
    const oracle::Problem p = testing::random_problem(rng, Start::moving, kind);
    const std::string what = describe(p, n, 29);
    const AxisLimits l = limits_of(p);
    const MotionState start{p.p0, p.v0, p.a0};
    const MotionState target{p.pf, p.vf, p.af};
    AxisProfile searched;
    ASSERT_EQ(searched.plan(start, target, l), AxisStatus::ok) << what;
    const double m = searched.min_duration();
    const auto fresh = [&](double T, bool expected) {
      AxisProfile axis;
      EXPECT_EQ(axis.plan(start, target, l), AxisStatus::ok) << what;
      unknown += axis.min_duration_known() ? 0 : 1;
      EXPECT_EQ(axis.reaches_by(T), expected) << what << ": at " << T << " s, the shortest is " << m;
      return axis;
    };
    fresh(m * (1.0 + 1e-9) + 1e-12, true);
    fresh(std::nextafter(m, 0.0) * (1.0 - 1e-6), false);
    double longer = m * stretch(rng) + 1e-3;
    for (std::size_t b = 0; b < searched.blocked_count(); ++b) {
      if (searched.blocked(b).contains(longer)) longer = searched.blocked(b).hi;
    }
    const AxisProfile asked = fresh(longer, true);
    JerkProfile with_check;
    JerkProfile without;
    ASSERT_TRUE(asked.build(longer, with_check)) << what;
    ASSERT_TRUE(searched.build(longer, without)) << what;
    ASSERT_EQ(with_check.size(), without.size()) << what;
    for (std::size_t i = 0; i < without.size(); ++i) {
      EXPECT_EQ(with_check.segment(i).jerk, without.segment(i).jerk) << what << " segment " << i;
      EXPECT_EQ(with_check.segment(i).duration, without.segment(i).duration) << what << " segment " << i;
    }
    // At another duration than the one checked, the kept evaluation is not taken.
    JerkProfile other;
    const double later = longer + 0.25;
    if (!searched.feasible(later)) continue;
    ASSERT_TRUE(asked.build(later, other)) << what;
    ASSERT_TRUE(searched.build(later, without)) << what;
    EXPECT_EQ(segments_end(other).position, segments_end(without).position) << what;
    EXPECT_EQ(other.duration(), without.duration()) << what;
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(unknown, 6000);
}

class AxisProfileRandom : public ::testing::TestWithParam<int> {};

// 4 x 35 000 problems and 10 000 starts beyond the limits, each in kParts parts
// (CELLCTL_PLANNER_PROBLEMS sets the count per test, CELLCTL_PLANNER_SEED the seed).
TEST_P(AxisProfileRandom, RestToRestMatchesTheIndependentOptimum) {
  EXPECT_EQ(run_random(Start::at_rest, Target::at_rest, 35000, 1, GetParam()), 0);
}
// Moving starts anywhere within the bounds: those that must overshoot are braked first.
TEST_P(AxisProfileRandom, MovingStartMatchesTheIndependentOptimum) {
  EXPECT_EQ(run_random(Start::moving, Target::at_rest, 35000, 2, GetParam()), 0);
}
TEST_P(AxisProfileRandom, MovingTargetMatchesTheIndependentOptimum) {
  EXPECT_EQ(run_random(Start::moving, Target::moving, 35000, 3, GetParam()), 0);
}
// With a target acceleration too: every plan optimal and exact, none refused (velocity gaps are
// blocked intervals, see velocity_gap).
TEST_P(AxisProfileRandom, AcceleratingTargetMatchesTheIndependentOptimum) {
  EXPECT_EQ(run_random(Start::moving, Target::accelerating, 35000, 4, GetParam()), 0);
}
// Starts beyond the limits, velocity and acceleration either side: braked, then optimal. Fewer in the
// suite: the brake oracle searches each start (about 6 ms a problem under ASan, 227 s for 35 000).
TEST_P(AxisProfileRandom, StartBeyondTheLimitsMatchesTheIndependentOptimum) {
  EXPECT_EQ(run_random(Start::beyond_limits, Target::moving, 10000, 7, GetParam()), 0);
}

INSTANTIATE_TEST_SUITE_P(Part, AxisProfileRandom, ::testing::Range(0, kParts));

}  // namespace
}  // namespace cellctl::planner

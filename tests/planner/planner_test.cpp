#include "planner/planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "planner/optimum_oracle.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::planner {
namespace {

constexpr double kDt = 0.001;

template <int N>
Input<N> at_rest(const Vector<N>& start, const Vector<N>& target, double v, double a, double j) {
  Input<N> in;
  in.current_position = start;
  in.target_position = target;
  in.max_velocity.setConstant(v);
  in.max_acceleration.setConstant(a);
  in.max_jerk.setConstant(j);
  return in;
}

// Steps the planner, checking every step against the limits of `in` by finite differences (a jump
// in position, velocity or acceleration shows up as a difference above limit x dt). Returns the
// number of steps to `finished`, or -1 when it did not finish within max_steps.
template <int N>
struct LimitChecker {
  double tolerance = 1e-9;  // relative, for rounding

  void check_step(const Input<N>& limits, const Input<N>& before, const Output<N>& after) const {
    for (int i = 0; i < N; ++i) {
      const double vmax = limits.max_velocity[i] * (1 + tolerance) + 1e-12;
      const double amax = limits.max_acceleration[i] * (1 + tolerance) + 1e-12;
      const double jmax = limits.max_jerk[i] * (1 + tolerance) + 1e-9;
      ASSERT_LE(std::abs(after.new_velocity[i]), vmax) << "axis " << i << " t " << after.time;
      ASSERT_LE(std::abs(after.new_acceleration[i]), amax) << "axis " << i << " t " << after.time;
      ASSERT_LE(std::abs(after.new_position[i] - before.current_position[i]) / kDt, vmax) << "axis " << i;
      ASSERT_LE(std::abs(after.new_velocity[i] - before.current_velocity[i]) / kDt, amax) << "axis " << i;
      ASSERT_LE(std::abs(after.new_acceleration[i] - before.current_acceleration[i]) / kDt, jmax)
          << "axis " << i << " t " << after.time;
    }
  }
};

template <int N>
int run_checked(Planner<N>& planner, Input<N>& in, Output<N>& out, int max_steps) {
  const LimitChecker<N> checker;
  for (int step = 1; step <= max_steps; ++step) {
    const Result r = planner.update(in, out);
    EXPECT_FALSE(is_error(r)) << to_string(r) << " for\n" << to_string(in);
    checker.check_step(in, in, out);
    if (::testing::Test::HasFatalFailure()) return -1;
    out.pass_to_input(in);
    if (r == Result::finished) return step;
  }
  return -1;
}

TEST(Planner, RejectsNonPositiveCycleAtConstruction) {
  EXPECT_THROW(Planner<1>{0.0}, std::invalid_argument);
  EXPECT_THROW(Planner<1>{-1e-3}, std::invalid_argument);
  EXPECT_THROW(Planner<1>{NAN}, std::invalid_argument);
}

TEST(Planner, LongMoveTakesTheClassicDurationAndArrivesExactly) {
  Planner<1> planner(kDt);
  Input<1> in = at_rest<1>(Vector<1>{0.0}, Vector<1>{10.0}, 1.0, 2.0, 10.0);
  Output<1> out;
  const int steps = run_checked(planner, in, out, 20000);
  EXPECT_NEAR(out.duration, 10.0 / 1.0 + 1.0 / 2.0 + 2.0 / 10.0, 1e-12);
  EXPECT_EQ(steps, static_cast<int>(std::ceil(10.7 / kDt - 1e-9)));
  EXPECT_TRUE(out.done);
  EXPECT_EQ(out.new_position[0], 10.0);  // exact, not near
  EXPECT_EQ(out.new_velocity[0], 0.0);
  EXPECT_EQ(out.new_acceleration[0], 0.0);
  // Once finished it stays finished at the target.
  EXPECT_EQ(planner.update(in, out), Result::finished);
  EXPECT_EQ(out.new_position[0], 10.0);
}

TEST(Planner, ZeroDistanceFinishesAtOnce) {
  Planner<2> planner(kDt);
  Input<2> in = at_rest<2>(Vector<2>{1.0, 2.0}, Vector<2>{1.0, 2.0}, 1.0, 1.0, 1.0);
  Output<2> out;
  EXPECT_EQ(planner.update(in, out), Result::finished);
  EXPECT_EQ(out.duration, 0.0);
  EXPECT_EQ(out.new_position, in.target_position);
}

TEST(Planner, PhaseSyncSlowestAxisSetsTheDurationAndAllProgressTogether) {
  Planner<3> planner(kDt);
  const Vector<3> start{1.0, -2.0, 0.5};
  const Vector<3> target{11.0, 0.0, -4.5};  // distances 10, 2, -5 with equal limits: axis 0 is slowest
  Input<3> in = at_rest<3>(start, target, 1.0, 2.0, 10.0);
  in.synchronization = Synchronization::phase;
  Output<3> out;
  const LimitChecker<3> checker;
  Result r = Result::working;
  int steps = 0;
  while (r == Result::working && steps < 20000) {
    r = planner.update(in, out);
    ++steps;
    checker.check_step(in, in, out);
    const Vector<3> progress = (out.new_position - start).cwiseQuotient(target - start);
    EXPECT_NEAR(progress[1], progress[0], 1e-12) << "t " << out.time;
    EXPECT_NEAR(progress[2], progress[0], 1e-12) << "t " << out.time;
    out.pass_to_input(in);
  }
  ASSERT_EQ(r, Result::finished);
  EXPECT_NEAR(out.duration, 10.7, 1e-12);  // axis 0 alone would take 10.7 s
  EXPECT_EQ(out.new_position, target);
}

TEST(Planner, PhaseSyncPathLimitIsTheTightestOverTheAxes) {
  // Axis 1 moves 1 at 0.05 max, axis 0 moves 10 at 1. On the straight line (path s: 0 -> 1) the
  // velocity limit comes from axis 1 (0.05/1 < 1/10), acceleration and jerk from axis 0 (2/10 and
  // 10/10): V = 0.05, A = 0.2, J = 1, and V > A^2/J so T = 1/V + V/A + A/J = 20 + 0.25 + 0.2.
  // That is longer than axis 1 alone (20.14 s): staying on the line costs the difference.
  Planner<2> planner(kDt);
  Input<2> in = at_rest<2>(Vector<2>{0.0, 0.0}, Vector<2>{10.0, 1.0}, 1.0, 2.0, 10.0);
  in.max_velocity[1] = 0.05;
  in.synchronization = Synchronization::phase;
  Output<2> out;
  ASSERT_GT(run_checked(planner, in, out, 60000), 0);
  EXPECT_NEAR(out.duration, 20.45, 1e-9);
  EXPECT_TRUE(out.note.empty());
  // Time synchronisation does not keep the line and is faster: axis 1 alone sets 20.14 s and
  // axis 0 (10.7 s alone) is stretched to it.
  Planner<2> timed(kDt);
  in = at_rest<2>(Vector<2>{0.0, 0.0}, Vector<2>{10.0, 1.0}, 1.0, 2.0, 10.0);
  in.max_velocity[1] = 0.05;
  ASSERT_GT(run_checked(timed, in, out, 60000), 0);
  EXPECT_NEAR(out.duration, 1.0 / 0.05 + 2.0 * std::sqrt(0.05 / 10.0), 1e-9);  // no acceleration plateau
}

TEST(Planner, RandomisedMovesStayWithinLimitsAndArrive) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> pos(-50.0, 50.0);
  std::uniform_real_distribution<double> lim(0.0, 1.0);
  for (int c = 0; c < 150; ++c) {
    Planner<3> planner(kDt);
    Input<3> in;
    for (int i = 0; i < 3; ++i) {
      in.current_position[i] = pos(rng);
      // Short and long moves alike: some never reach the velocity or acceleration limit.
      in.target_position[i] = in.current_position[i] + pos(rng) * std::pow(10.0, -3.0 * lim(rng));
      in.max_velocity[i] = 1.0 + 99.0 * lim(rng);
      in.max_acceleration[i] = 10.0 + 990.0 * lim(rng);
      in.max_jerk[i] = 100.0 + 9900.0 * lim(rng);
    }
    const Vector<3> target = in.target_position;
    Output<3> out;
    const int steps = run_checked(planner, in, out, 200000);
    ASSERT_GT(steps, 0) << "case " << c;
    EXPECT_EQ(steps, static_cast<int>(std::ceil(out.duration / kDt - 1e-9))) << "case " << c;
    EXPECT_EQ(out.new_position, target) << "case " << c;
  }
}

TEST(Planner, NewTargetMidMotionStopsSmoothlyThenGoes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-20.0, 20.0);
  std::uniform_int_distribution<int> when(1, 3000);
  for (int c = 0; c < 60; ++c) {
    Planner<2> planner(kDt);
    Input<2> in = at_rest<2>(Vector<2>{0.0, 0.0}, Vector<2>{pos(rng), pos(rng)}, 10.0, 20.0, 200.0);
    in.max_velocity[1] = 4.0;
    Output<2> out;
    const LimitChecker<2> checker;
    // Change the target twice while moving; every step is checked against the limits, so a jump
    // in position, velocity or acceleration at the switch fails the finite differences.
    for (int retarget = 0; retarget < 2; ++retarget) {
      for (int k = when(rng); k > 0; --k) {
        if (planner.update(in, out) == Result::finished) break;
        checker.check_step(in, in, out);
        ASSERT_FALSE(HasFatalFailure()) << "case " << c;
        out.pass_to_input(in);
      }
      in.target_position = Vector<2>{pos(rng), pos(rng)};
    }
    const Vector<2> target = in.target_position;
    ASSERT_GT(run_checked(planner, in, out, 100000), 0) << "case " << c;
    EXPECT_EQ(out.new_position, target);
  }
}

TEST(Planner, RetargetWhileCruisingReversesWithoutStoppingFirst) {
  Planner<1> planner(kDt);
  Input<1> in = at_rest<1>(Vector<1>{0.0}, Vector<1>{10.0}, 1.0, 2.0, 10.0);
  Output<1> out;
  for (int k = 0; k < 5000; ++k) {  // 5 s: cruising at 1
    ASSERT_EQ(planner.update(in, out), Result::working);
    out.pass_to_input(in);
  }
  ASSERT_NEAR(in.current_velocity[0], 1.0, 1e-12);
  // Back to 0 from (x, 1, 0): the reversal is one profile, no stop-and-replan; with V = 1, A = 2,
  // J = 10 it takes the brake's 0.7 s only once (the old stop-first plan: 0.7 s + a move from rest).
  const double x = in.current_position[0];
  // Stopping alone (to a = 0) covers 0.35 in 0.7 s; reversing keeps a = -2 through the apex:
  // 0.2 s ramping to -2 (0.2 - 10 * 0.2^3 / 6), then 0.4 s at -2 from 0.8 to 0 (0.16).
  const double reversal_position = x + 0.2 - 10.0 * 0.008 / 6.0 + 0.16;
  in.target_position[0] = 0.0;
  ASSERT_EQ(planner.update(in, out), Result::working);
  const double stop_and_replan = 0.7 + ((x + 0.35) / 1.0 + 0.5 + 0.2);
  EXPECT_LE(out.duration, stop_and_replan + 1e-9);
  const double best = oracle::min_duration(
      oracle::Problem{x, 1.0, 0.0, 0.0, 0.0, 0.0, oracle::Limits{1.0, -1.0, 2.0, -2.0, 10.0}},
      2 * stop_and_replan);
  EXPECT_NEAR(out.duration, best, 1e-9 * best);
  EXPECT_LT(out.duration, stop_and_replan - 0.1);  // 6.2 s against 6.4 s
  const PositionExtrema e = planner.trajectory().position_extrema(0);
  EXPECT_NEAR(e.max.position, reversal_position, 1e-9);
  EXPECT_NEAR(e.max.time, 0.6, 1e-9);
  double furthest = 0.0;
  const LimitChecker<1> checker;
  do {
    checker.check_step(in, in, out);
    furthest = std::max(furthest, out.new_position[0]);
    out.pass_to_input(in);
  } while (planner.update(in, out) == Result::working);
  EXPECT_NEAR(furthest, reversal_position, 1e-6);  // sampled at 1 ms around the apex
  EXPECT_EQ(out.new_position[0], 0.0);
}

TEST(Planner, DisabledAxisPassesThroughAndIsNotValidated) {
  Planner<2> planner(kDt);
  Input<2> in = at_rest<2>(Vector<2>{0.0, 3.0}, Vector<2>{1.0, 100.0}, 1.0, 2.0, 10.0);
  in.enabled[1] = false;
  in.max_jerk[1] = 0.0;  // would be invalid if the axis were planned
  Output<2> out;
  ASSERT_GT(run_checked(planner, in, out, 10000), 0);
  EXPECT_EQ(out.new_position[0], 1.0);
  EXPECT_EQ(out.new_position[1], 3.0);
}

TEST(Planner, InvalidInputIsAnErrorNamingTheAxis) {
  Planner<3> planner(kDt);
  Input<3> in = at_rest<3>(Vector<3>{0, 0, 0}, Vector<3>{1, 1, 1}, 1.0, 2.0, 10.0);
  Output<3> out;
  out.new_position = Vector<3>{7, 7, 7};

  Input<3> bad = in;
  bad.max_jerk[1] = 0.0;
  EXPECT_EQ(planner.update(bad, out), Result::invalid_limits);
  EXPECT_EQ(out.error_axis, 1);
  EXPECT_EQ(out.new_position, (Vector<3>{7, 7, 7}));  // output untouched on error

  bad = in;
  bad.max_velocity[2] = -1.0;
  EXPECT_EQ(planner.update(bad, out), Result::invalid_limits);
  EXPECT_EQ(out.error_axis, 2);

  bad = in;
  bad.max_acceleration[0] = INFINITY;
  EXPECT_EQ(planner.update(bad, out), Result::invalid_limits);
  EXPECT_EQ(out.error_axis, 0);

  bad = in;
  bad.target_position[2] = NAN;
  EXPECT_EQ(planner.update(bad, out), Result::invalid_state);
  EXPECT_EQ(out.error_axis, 2);
  EXPECT_NE(to_string(Result::invalid_state).find("not finite"), std::string_view::npos);

  EXPECT_EQ(planner.update(in, out), Result::working);  // recovers with a valid input
  EXPECT_EQ(out.error_axis, -1);
}

TEST(Planner, UpdateNeverAllocates) {
  Planner<6> planner(kDt);
  Input<6> in;
  in.target_position.setConstant(2.0);
  Output<6> out;
  const std::size_t before = cellctl::testing::allocation_count();
  for (int k = 0; k < 3000; ++k) {
    if (k == 1000) in.target_position.setConstant(-1.0);  // a replan mid-motion
    (void)planner.update(in, out);
    out.pass_to_input(in);
  }
  EXPECT_EQ(cellctl::testing::allocation_count() - before, 0u);
  // The counter itself works: an allocation is seen.
  const auto* probe = new std::vector<int>(3);
  EXPECT_GT(cellctl::testing::allocation_count() - before, 0u);
  delete probe;
}

}  // namespace
}  // namespace cellctl::planner

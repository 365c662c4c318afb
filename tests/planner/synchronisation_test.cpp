// Multi-axis planning: time synchronisation against the independent optimum, blocked intervals
// in synchronisation, phase synchronisation and its fallback, none, the trajectory object and the
// printable input (the travel and refused targets: travel_test.cpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "planner/arrival_check.hpp"
#include "planner/brake_oracle.hpp"
#include "planner/optimum_oracle.hpp"
#include "planner/planner.hpp"
#include "planner/random_problems.hpp"
#include "planner/segments_end.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::planner {
namespace {

template <int N>
void random_time_sync(testing::Start start, long fallback, std::uint64_t fallback_seed) {
  const long count = testing::problem_count(fallback) / 10;  // each is N problems and a common search
  const std::uint64_t seed = testing::problem_seed(fallback_seed);
  std::mt19937_64 rng(seed);
  for (long c = 0; c < count && !::testing::Test::HasFailure(); ++c) {
    std::vector<oracle::Problem> axes;
    for (int i = 0; i < N; ++i) axes.push_back(testing::random_problem(rng, start));
    const Input<N> in = testing::input_of<N>(axes);
    Trajectory<N> t;
    int axis = -1;
    const std::string what =
        "case " + std::to_string(c) + " seed " + std::to_string(seed) + "\n" + to_string(in);
    ASSERT_EQ(Trajectory<N>::calculate(in, t, axis), Result::working) << what;
    // The oracle's own brake ends where its reach first touches the safe states, tangentially as a
    // rule: its end state is found to about the square root of rounding (1e-8), and the duration
    // from there moves by as much. The axis tests check the brake and what follows it one by one
    // at 1e-9 (axis_profile_test.cpp).
    const bool braked = std::any_of(axes.begin(), axes.end(),
                                    [](const oracle::Problem& p) { return oracle::braked(p).delay > 0.0; });
    EXPECT_TRUE(oracle::confirms_min_common_duration(axes, t.duration(), braked ? 1e-7 : 1e-9))
        << what << "\nplanned " << t.duration() << " s, optimum "
        << oracle::min_common_duration(axes, 1.01 * t.duration() + 1e-9);
    expect_arrives_together(t, in, what);
  }
}

TEST(TimeSync, ThreeAxesFromRestAtTheIndependentOptimum) {
  random_time_sync<3>(testing::Start::at_rest, 10000, 5);
}
TEST(TimeSync, SixAxesFromMovingStatesAtTheIndependentOptimum) {
  random_time_sync<6>(testing::Start::moving, 10000, 6);
}

// An axis that did not set the common duration is not searched for its own shortest one in
// calculate() (AxisProfile::reaches_by): asked, the trajectory searches it then, and it is the one
// the axis planned alone has (whose search the random axis tests check against the independent
// optimum); the common duration is the longest of them. Time synchronisation with and without a
// travel (the scratch trajectory copied into the caller's), none, a disabled axis, and the answers
// of a copy of the trajectory, assigned over one that held another plan.
TEST(TimeSync, AnAxisShortestDurationIsItsOwnWhenAsked) {
  std::mt19937_64 rng(31);
  Trajectory<6> earlier;  // holds the plan before, overwritten by each copy
  for (int c = 0; c < 2000; ++c) {
    std::vector<oracle::Problem> axes;
    for (int i = 0; i < 6; ++i) axes.push_back(testing::random_problem(rng, testing::Start::moving));
    Input<6> in = testing::input_of<6>(axes);
    const int variant = c % 4;
    if (variant == 1) {
      for (int i = 0; i < 6; ++i) {  // a travel far wider than any motion here
        in.min_position[i] = std::min(in.current_position[i], in.target_position[i]) - 100.0;
        in.max_position[i] = std::max(in.current_position[i], in.target_position[i]) + 100.0;
      }
    }
    if (variant == 2) in.synchronization = Synchronization::none;
    if (variant == 3) in.enabled[4] = false;
    const std::string what = "case " + std::to_string(c) + "\n" + to_string(in);
    Trajectory<6> t;
    int axis = -1;
    ASSERT_EQ(Trajectory<6>::calculate(in, t, axis), Result::working) << what;
    earlier = t;
    double longest = 0.0;
    for (int i = 0; i < 6; ++i) {
      if (!in.enabled[static_cast<std::size_t>(i)]) {
        EXPECT_EQ(earlier.axis_min_duration(i), 0.0) << what;
        continue;
      }
      const oracle::Problem& p = axes[static_cast<std::size_t>(i)];
      AxisProfile alone;
      ASSERT_EQ(alone.plan({p.p0, p.v0, p.a0}, {p.pf, p.vf, p.af},
                           {p.limits.vmax, p.limits.vmin, p.limits.amax, p.limits.amin, p.limits.jerk}),
                AxisStatus::ok);
      EXPECT_EQ(t.axis_min_duration(i), alone.min_duration()) << what << " axis " << i;
      EXPECT_EQ(earlier.axis_min_duration(i), alone.min_duration()) << what << " axis " << i << " (copy)";
      longest = std::max(longest, alone.min_duration());
    }
    EXPECT_EQ(t.duration(), longest) << what;
    if (::testing::Test::HasFailure()) break;
  }
}

TEST(TimeSync, SkipsAnAxisBlockedInterval) {
  // Axis 0 cruises at -2 (its min velocity) and must arrive 2 further at -2: 1 s at once, or
  // slower by braking a little, up to 1.2835 s; then nothing until it can turn around (3.1165 s).
  // Axis 1 alone needs 2 s: the common duration is the end of axis 0's blocked interval.
  const std::vector<oracle::Problem> axes{
      {0.0, -2.0, 0.0, -2.0, -2.0, 0.0, {2.0, -2.0, 2.0, -2.0, 10.0}},
      {0.0, 0.0, 0.0, 3.0, 0.0, 0.0, {2.0, -2.0, 2.0, -2.0, 10.0}},
  };
  const Input<2> in = testing::input_of<2>(axes);
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_NEAR(t.axis_min_duration(0), 1.0, 1e-12);
  ASSERT_EQ(t.blocked_count(0), 1u);
  const Interval& b = t.blocked(0, 0);
  EXPECT_NEAR(b.lo, 1.283484861, 1e-8);
  EXPECT_NEAR(b.hi, 3.116515139, 1e-8);
  EXPECT_EQ(t.blocked_count(1), 0u);
  EXPECT_GT(t.axis_min_duration(1), b.lo);
  EXPECT_LT(t.axis_min_duration(1), b.hi);
  EXPECT_DOUBLE_EQ(t.duration(), b.hi);
  // The independent check: inside the interval axis 0 has no motion, at its ends it has one.
  for (const double f : {0.01, 0.3, 0.5, 0.7, 0.99}) {
    EXPECT_FALSE(oracle::feasible(axes[0], b.lo + f * (b.hi - b.lo))) << f;
  }
  EXPECT_TRUE(oracle::feasible(axes[0], b.lo * (1 - 1e-9)));
  EXPECT_TRUE(oracle::feasible(axes[0], b.hi * (1 + 1e-9)));
  EXPECT_TRUE(oracle::confirms_min_common_duration(axes, t.duration(), 1e-9));
  expect_arrives_together(t, in, "blocked");
}

TEST(TimeSync, AnAxisAlreadyThereButMovingBlocksUntilItCanComeBack) {
  // At its target position with its target velocity -2: 0 s alone; any other duration up to 4.4 s
  // would have to leave and come back.
  const std::vector<oracle::Problem> axes{
      {0.0, -2.0, 0.0, 0.0, -2.0, 0.0, {2.0, -2.0, 2.0, -2.0, 10.0}},
      {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, {2.0, -2.0, 2.0, -2.0, 10.0}},
  };
  const Input<2> in = testing::input_of<2>(axes);
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_EQ(t.axis_min_duration(0), 0.0);
  ASSERT_EQ(t.blocked_count(0), 1u);
  EXPECT_NEAR(t.blocked(0, 0).hi, 4.4, 1e-9);
  EXPECT_NEAR(t.duration(), 4.4, 1e-9);
  EXPECT_TRUE(oracle::confirms_min_common_duration(axes, t.duration(), 1e-9));
  expect_arrives_together(t, in, "already there");
}

TEST(TimeSync, ZeroLengthAxisStaysExactlyPut) {
  Input<2> in;
  in.current_position = Vector<2>{1.5, -0.25};
  in.target_position = Vector<2>{4.0, -0.25};
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_GT(t.duration(), 0.0);
  for (int k = 0; k <= 100; ++k) {
    const MotionState s = t.profile(1).at(t.duration() * k / 100.0);
    EXPECT_EQ(s.position, -0.25);
    EXPECT_EQ(s.velocity, 0.0);
    EXPECT_EQ(s.acceleration, 0.0);
  }
}

TEST(NoSync, EachAxisOnItsOwnOptimum) {
  Input<2> in;
  in.target_position = Vector<2>{4.0, 0.5};
  in.synchronization = Synchronization::none;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_DOUBLE_EQ(t.profile(0).duration(), t.axis_min_duration(0));
  EXPECT_DOUBLE_EQ(t.profile(1).duration(), t.axis_min_duration(1));
  EXPECT_LT(t.profile(1).duration(), t.profile(0).duration());
  EXPECT_DOUBLE_EQ(t.duration(), t.axis_min_duration(0));
  Vector<2> p, v, a, j;
  t.at_time(t.duration(), p, v, a, j);
  EXPECT_NEAR(p[1], 0.5, 1e-12);  // held at its target after its own end
}

TEST(PhaseSync, MovingOnTheLineKeepsTheLine) {
  // Both axes move along the direction (2, 1) to the target: the states are on the line.
  Input<2> in;
  in.current_velocity = Vector<2>{0.4, 0.2};
  in.current_acceleration = Vector<2>{-0.2, -0.1};
  in.target_position = Vector<2>{2.0, 1.0};
  in.synchronization = Synchronization::phase;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_EQ(t.synchronization(), Synchronization::phase);
  EXPECT_TRUE(t.note().empty());
  for (int k = 0; k <= 100; ++k) {
    const double time = t.duration() * k / 100.0;
    EXPECT_NEAR(t.profile(0).at(time).position, 2.0 * t.profile(1).at(time).position, 1e-12);
  }
  EXPECT_NEAR(segments_end(t.profile(0)).position, 2.0, 1e-9);
}

TEST(PhaseSync, OffTheLineFallsBackToTimeSyncWithANote) {
  Input<2> in;
  in.current_velocity = Vector<2>{0.4, -0.3};  // not along the displacement (2, 1)
  in.target_position = Vector<2>{2.0, 1.0};
  in.synchronization = Synchronization::phase;
  Planner<2> planner(0.001);
  Output<2> out;
  ASSERT_EQ(planner.update(in, out), Result::working);
  EXPECT_EQ(planner.trajectory().synchronization(), Synchronization::time);
  EXPECT_EQ(out.note, kPhaseFallbackNote);
  Input<2> timed = in;
  timed.synchronization = Synchronization::time;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(timed, t, axis), Result::working);
  EXPECT_DOUBLE_EQ(planner.trajectory().duration(), t.duration());
}

TEST(PhaseSync, ATargetBeyondTheLinesLimitsFallsBackToTimeSyncWithANote) {
  // Along (1, 1) the line's jerk is axis 0's (10) and its lowest velocity axis 1's (-0.01). Arriving
  // at 0.5 m/s^2 along the line needs 0.5^2 / (2 * 10) = 0.0125 m/s less velocity just before: below
  // the line's -0.01. Each axis alone can (axis 0 down to -1, axis 1 needs only 0.00125 at jerk 100).
  Input<2> in;
  in.target_position = Vector<2>{1.0, 1.0};
  in.target_acceleration = Vector<2>{0.5, 0.5};
  in.max_acceleration = Vector<2>{2.0, 2.0};
  in.max_jerk = Vector<2>{10.0, 100.0};
  in.min_velocity = Vector<2>{-1.0, -0.01};
  in.synchronization = Synchronization::phase;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working) << axis;
  EXPECT_EQ(t.synchronization(), Synchronization::time);
  EXPECT_EQ(t.note(), kPhaseLimitsNote);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(segments_end(t.profile(i)).position, 1.0, 1e-9);
    EXPECT_NEAR(segments_end(t.profile(i)).acceleration, 0.5, 1e-9);
    EXPECT_NEAR(t.profile(i).duration(), t.duration(), 1e-12);
  }
}

TEST(PhaseSync, AStartBeyondTheLinesLimitsBrakesEachAxisWithinItsOwn) {
  // On the line (1, 1), both axes at v 0.009 and a 0.3. Axis 1 alone (jerk 100) ramps its
  // acceleration out within 0.3^2 / 200 = 0.00045 of velocity: 0.00945, under its limit of 0.01.
  // Along the line the jerk is axis 0's 10, and the velocity limit axis 1's: a brake along the line
  // took axis 1 to 0.0135.
  Input<2> in;
  in.current_velocity = Vector<2>{0.009, 0.009};
  in.current_acceleration = Vector<2>{0.3, 0.3};
  in.target_position = Vector<2>{1.0, 1.0};
  in.max_velocity = Vector<2>{1.0, 0.01};
  in.max_acceleration = Vector<2>{2.0, 2.0};
  in.max_jerk = Vector<2>{10.0, 100.0};
  in.synchronization = Synchronization::phase;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working) << axis;
  EXPECT_EQ(t.synchronization(), Synchronization::time);
  EXPECT_EQ(t.note(), kPhaseBrakeNote);
  double fastest = 0.0;
  for (int k = 0; k <= 20000; ++k) {
    fastest = std::max(fastest, t.profile(1).at(t.duration() * k / 20000.0).velocity);
  }
  EXPECT_LE(fastest, 0.01 + 1e-9);
  EXPECT_NEAR(segments_end(t.profile(1)).position, 1.0, 1e-9);
}

TEST(PhaseSync, NoDisplacementButMovingIsTimeSynchronisedWithANote) {
  Input<2> in;
  in.current_velocity = Vector<2>{0.5, -0.2};
  in.synchronization = Synchronization::phase;
  Trajectory<2> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_EQ(t.synchronization(), Synchronization::time);
  EXPECT_EQ(t.note(), kPhaseFallbackNote);
  // At rest where it is: nothing moves, no note.
  in.current_velocity = Vector<2>{0.0, 0.0};
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis), Result::working);
  EXPECT_TRUE(t.note().empty());
}

TEST(Input, PrintsItselfForErrorMessages) {
  Input<2> in;
  in.current_position = Vector<2>{1.25, 0.0};
  in.target_position = Vector<2>{3.5, 0.0};
  in.min_velocity[0] = -0.5;
  in.max_position[0] = 4.0;
  in.enabled[1] = false;
  const std::string s = to_string(in);
  EXPECT_NE(s.find("synchronization time"), std::string::npos) << s;
  EXPECT_NE(s.find("axis 0: p 1.25 v 0 a 0 -> p 3.5 v 0 a 0; v [-0.5, 1] a [-1, 1] j 1; travel [-inf, 4]"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("axis 1: disabled"), std::string::npos) << s;
}

TEST(Planner, ReplansFromMovingStatesWithoutAllocating) {
  Planner<6> planner(0.001);
  Input<6> in;
  in.target_position.setConstant(2.0);
  in.max_velocity.setConstant(1.5);
  in.target_position[3] = -1.0;
  Output<6> out;
  const std::size_t before = cellctl::testing::thread_allocation_count();
  for (int k = 0; k < 4000; ++k) {
    if (k % 700 == 350) in.target_position *= -0.5;  // replans from moving states
    if (k == 2000) in.synchronization = Synchronization::phase;
    ASSERT_FALSE(is_error(planner.update(in, out)));
    out.pass_to_input(in);
  }
  EXPECT_EQ(cellctl::testing::thread_allocation_count() - before, 0u);
}

}  // namespace
}  // namespace cellctl::planner

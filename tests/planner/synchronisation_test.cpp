// Multi-axis planning: time synchronisation against the independent optimum, blocked intervals
// in synchronisation, phase synchronisation and its fallback, none, the travel, the trajectory
// object and the printable input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "planner/brake_oracle.hpp"
#include "planner/optimum_oracle.hpp"
#include "planner/planner.hpp"
#include "planner/random_problems.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::planner {
namespace {

// Every axis ends in its target exactly at the common duration, within its limits throughout.
template <int N>
void expect_arrives_together(const Trajectory<N>& t, const Input<N>& in, const std::string& what) {
  for (int i = 0; i < N; ++i) {
    const JerkProfile& p = t.profile(i);
    EXPECT_NEAR(p.duration(), t.duration(), 1e-9 * (1.0 + t.duration())) << what << " axis " << i;
    EXPECT_NEAR(p.end().position, in.target_position[i], 1e-8) << what << " axis " << i;
    EXPECT_NEAR(p.end().velocity, in.target_velocity[i], 1e-8) << what << " axis " << i;
    EXPECT_NEAR(p.end().acceleration, 0.0, 1e-8) << what << " axis " << i;
    // Within the limits from the end of a brake on: once a state from which they can be kept.
    const oracle::Limits l{in.max_velocity[i], -in.max_velocity[i], in.max_acceleration[i],
                           -in.max_acceleration[i], in.max_jerk[i]};
    bool braked = oracle::in_safe_set(p.start().velocity, p.start().acceleration, l);
    for (int k = 0; k <= 200; ++k) {
      const MotionState s = p.at(t.duration() * k / 200.0);
      if (!braked) {
        braked = oracle::in_safe_set(s.velocity, s.acceleration, l);
        continue;
      }
      EXPECT_LE(std::abs(s.velocity), in.max_velocity[i] + 1e-9) << what << " axis " << i;
      EXPECT_LE(std::abs(s.acceleration), in.max_acceleration[i] + 1e-9) << what << " axis " << i;
    }
  }
}

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
  EXPECT_NEAR(t.profile(0).end().position, 2.0, 1e-9);
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

TEST(Travel, TargetOutsideIsRefusedNamingTheAxis) {
  Input<2> in;
  in.target_position = Vector<2>{1.0, 5.0};
  in.max_position = Vector<2>{10.0, 4.0};
  Trajectory<2> t;
  int axis = -1;
  TravelExcess excess;
  EXPECT_EQ(Trajectory<2>::calculate(in, t, axis, &excess), Result::outside_travel);
  EXPECT_EQ(axis, 1);
  EXPECT_TRUE(excess.beyond_max);
  EXPECT_NEAR(excess.by, 1.0, 1e-12);
  EXPECT_NE(to_string(Result::outside_travel).find("travel"), std::string_view::npos);
  // Below min_position, through the planner's output.
  in.target_position = Vector<2>{-3.0, 1.0};
  in.min_position = Vector<2>{-2.5, -10.0};
  Planner<2> planner(0.001);
  Output<2> out;
  EXPECT_EQ(planner.update(in, out), Result::outside_travel);
  EXPECT_EQ(out.error_axis, 0);
  EXPECT_FALSE(out.travel_excess.beyond_max);
  EXPECT_NEAR(out.travel_excess.by, 0.5, 1e-12);
}

TEST(Travel, UnavoidableOvershootIsRefusedAndAStopInsideIsNot) {
  // Cruising at 1 towards max_position 10, 0.2 before it: stopping needs 0.35 (V 1, A 2, J 10).
  Input<1> in;
  in.current_position[0] = 9.8;
  in.current_velocity[0] = 1.0;
  in.target_position[0] = 9.9;
  in.max_acceleration[0] = 2.0;
  in.max_jerk[0] = 10.0;
  in.max_position[0] = 10.0;
  Trajectory<1> t;
  int axis = -1;
  TravelExcess excess;
  EXPECT_EQ(Trajectory<1>::calculate(in, t, axis, &excess), Result::outside_travel);
  EXPECT_EQ(axis, 0);
  EXPECT_TRUE(excess.beyond_max);
  // The turn: -J to -2 (0.2 s, 0.18667 on), held until the velocity is zero (0.4 s, 0.16 on): 9.8 +
  // 0.34667 - 10 (not the 0.35 of a stop at rest: the turn goes on reversing).
  EXPECT_NEAR(excess.by, 0.2 - 10.0 * 0.2 * 0.2 * 0.2 / 6.0 + 0.16 - 0.2, 1e-9);
  in.max_position[0] = 10.2;  // room for the overshoot (9.8 + 0.35 = 10.15): planned, and it turns back
  ASSERT_EQ(Trajectory<1>::calculate(in, t, axis), Result::working);
  const PositionExtrema e = t.position_extrema(0);
  EXPECT_LE(e.max.position, 10.2);
  EXPECT_GT(e.max.position, 9.9);
  EXPECT_GT(e.max.time, 0.0);
  EXPECT_LT(e.max.time, t.duration());
  EXPECT_NEAR(t.profile(0).at(e.max.time).velocity, 0.0, 1e-9);
}

TEST(Travel, AnAxisSlowedForTheOthersKeepsTheTravelItsOwnMotionKeeps) {
  // Axis 0 moves away from its target 0.15 above min_position: turning at once it stops 0.041
  // above it. Axis 1's long move sets the common duration, at which axis 0's blend of extremes
  // turned late, 0.12 below min_position: this was refused (outside_travel) before travel_fit.hpp.
  Input<2> in;
  in.current_position = Vector<2>{0.15, 0.0};
  in.current_velocity = Vector<2>{-0.5, 0.0};
  in.target_position = Vector<2>{0.5, 10.0};
  in.max_acceleration = Vector<2>{2.0, 2.0};
  in.max_jerk = Vector<2>{10.0, 10.0};
  in.min_position = Vector<2>{0.0, -100.0};
  in.max_position = Vector<2>{1.0, 100.0};
  Trajectory<2> t;
  int axis = -1;
  TravelExcess excess;
  ASSERT_EQ(Trajectory<2>::calculate(in, t, axis, &excess), Result::working)
      << "axis " << axis << " by " << excess.by;
  EXPECT_GT(t.duration(), t.axis_min_duration(0) + 5.0);
  expect_arrives_together(t, in, "slowed axis");
  EXPECT_GE(t.position_extrema(0).min.position, -1e-12);
  EXPECT_LE(t.position_extrema(0).max.position, 0.5 + 1e-12);
  // Not the shortest motion held at the target: it arrives with axis 1 (still moving just before).
  EXPECT_GT(std::abs(t.profile(0).at(t.duration() - 0.01).velocity), 1e-6);
  // Where its own motion leaves the travel too, that motion's excess is what the refusal says.
  in.current_position[0] = 0.03;
  EXPECT_EQ(Trajectory<2>::calculate(in, t, axis, &excess), Result::outside_travel);
  EXPECT_EQ(axis, 0);
  EXPECT_FALSE(excess.beyond_max);
  EXPECT_NEAR(excess.by, 0.15 - 0.0408333 - 0.03, 1e-6);
}

TEST(Travel, WhereTheShortestMotionOvershootsTheTravelTurningAtOnceMayNot) {
  // 1 m/s towards max_position 0.347, target 0.345 behind the stop (A 2, J 10): the shortest motion
  // turns late and peaks at 0.3483; turning at full jerk at once peaks at 0.34667 and then goes
  // back. Refused (outside_travel, by 0.0013) before turn_first.
  Input<1> in;
  in.current_velocity[0] = 1.0;
  in.target_position[0] = 0.345;
  in.max_acceleration[0] = 2.0;
  in.max_jerk[0] = 10.0;
  Trajectory<1> t;
  int axis = -1;
  ASSERT_EQ(Trajectory<1>::calculate(in, t, axis), Result::working);
  const double shortest = t.duration();
  EXPECT_NEAR(t.position_extrema(0).max.position, 0.348299, 1e-6);
  in.max_position[0] = 0.347;
  for (const Synchronization sync : {Synchronization::none, Synchronization::time}) {
    in.synchronization = sync;
    TravelExcess excess;
    ASSERT_EQ(Trajectory<1>::calculate(in, t, axis, &excess), Result::working)
        << to_string(sync) << ": by " << excess.by;
    EXPECT_GT(t.duration(), shortest) << to_string(sync);
    // Alone: the turn itself; time-synchronised: mixed with the blend, as near it as the travel lets.
    if (sync == Synchronization::none) {
      EXPECT_NEAR(t.position_extrema(0).max.position, 0.2 - 10.0 * 0.2 * 0.2 * 0.2 / 6.0 + 0.16, 1e-9);
    } else {
      EXPECT_LE(t.position_extrema(0).max.position, 0.347 + 1e-12);
    }
    expect_arrives_together(t, in, std::string(to_string(sync)));
  }
  // Beside a slower axis, its turn mixed with the blend at the common duration; beside a faster
  // one, the common duration raised to its turn's.
  for (const double other : {20.0, 0.01}) {
    Input<2> two;
    two.current_velocity = Vector<2>{1.0, 0.0};
    two.target_position = Vector<2>{0.345, other};
    two.max_acceleration = Vector<2>{2.0, 2.0};
    two.max_jerk = Vector<2>{10.0, 10.0};
    two.max_position = Vector<2>{0.347, 100.0};
    Trajectory<2> t2;
    TravelExcess excess;
    ASSERT_EQ(Trajectory<2>::calculate(two, t2, axis, &excess), Result::working)
        << "other " << other << ": by " << excess.by;
    EXPECT_LE(t2.position_extrema(0).max.position, 0.347 + 1e-12) << "other " << other;
    expect_arrives_together(t2, two, "beside " + std::to_string(other));
  }
  // Where turning at once still leaves it, the refusal says by how much that turn does.
  in.max_position[0] = 0.3466;
  TravelExcess excess;
  EXPECT_EQ(Trajectory<1>::calculate(in, t, axis, &excess), Result::outside_travel);
  EXPECT_TRUE(excess.beyond_max);
  EXPECT_NEAR(excess.by, 0.2 - 10.0 * 0.2 * 0.2 * 0.2 / 6.0 + 0.16 - 0.3466, 1e-9);
}

// Random time-synchronised problems whose travel each axis's own shortest motion keeps (its
// extremes, the target's side a little further): every one is planned, inside the travel.
TEST(Travel, EveryAxisWhoseOwnMotionKeepsTheTravelIsPlannedInsideIt) {
  constexpr int kAxes = 3;
  const long count = testing::problem_count(35000) / 10;
  const std::uint64_t seed = testing::problem_seed(17);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> room(0.0, 0.05);
  long fitted = 0;
  for (long c = 0; c < count && !::testing::Test::HasFailure(); ++c) {
    std::vector<oracle::Problem> axes;
    for (int i = 0; i < kAxes; ++i) axes.push_back(testing::random_problem(rng, testing::Start::moving));
    Input<kAxes> in = testing::input_of<kAxes>(axes);
    Input<kAxes> alone = in;
    alone.synchronization = Synchronization::none;
    Trajectory<kAxes> t;
    int axis = -1;
    ASSERT_EQ(Trajectory<kAxes>::calculate(alone, t, axis), Result::working);
    for (int i = 0; i < kAxes; ++i) {
      const PositionExtrema e = t.position_extrema(i);
      in.min_position[i] = e.min.position - room(rng);
      in.max_position[i] = e.max.position + room(rng);
    }
    Trajectory<kAxes> unbounded;
    Input<kAxes> free = in;
    free.min_position.setConstant(-kInf);
    free.max_position.setConstant(kInf);
    ASSERT_EQ(Trajectory<kAxes>::calculate(free, unbounded, axis), Result::working);
    const std::string what =
        "case " + std::to_string(c) + " seed " + std::to_string(seed) + "\n" + to_string(in);
    TravelExcess excess;
    ASSERT_EQ(Trajectory<kAxes>::calculate(in, t, axis, &excess), Result::working)
        << what << "\naxis " << axis << " by " << excess.by;
    EXPECT_EQ(t.duration(), unbounded.duration()) << what;
    for (int i = 0; i < kAxes; ++i) {
      const PositionExtrema e = t.position_extrema(i);
      EXPECT_GE(e.min.position, in.min_position[i] - 1e-9) << what << " axis " << i;
      EXPECT_LE(e.max.position, in.max_position[i] + 1e-9) << what << " axis " << i;
      const JerkProfile& a = t.profile(i);
      const JerkProfile& b = unbounded.profile(i);
      bool same = a.size() == b.size();
      for (std::size_t k = 0; same && k < a.size(); ++k) {
        same = a.segment(k).jerk == b.segment(k).jerk && a.segment(k).duration == b.segment(k).duration;
      }
      if (!same) ++fitted;
    }
    expect_arrives_together(t, in, what);
  }
  std::printf("%ld axes of %ld kept in their travel by another profile than without it (seed %llu)\n", fitted,
              count * kAxes, static_cast<unsigned long long>(seed));
}

TEST(TargetLimits, ARefusedTargetSaysWhichLimitAndByHowMuch) {
  Input<2> in;  // V 1, A 1, J 1 on both axes
  in.target_position = Vector<2>{1.0, 2.0};
  in.target_velocity = Vector<2>{0.0, 1.5};
  Trajectory<2> t;
  int axis = -1;
  TargetExcess excess;
  EXPECT_EQ(Trajectory<2>::calculate(in, t, axis, nullptr, &excess), Result::target_outside_limits);
  EXPECT_EQ(axis, 1);
  EXPECT_EQ(excess.limit, TargetLimit::max_velocity);
  EXPECT_NEAR(excess.by, 0.5, 1e-12);
  // An acceleration beyond its bound, through the planner's output.
  in.target_velocity = Vector<2>{0.0, 0.0};
  in.target_acceleration = Vector<2>{-3.0, 0.0};
  Planner<2> planner(0.001);
  Output<2> out;
  EXPECT_EQ(planner.update(in, out), Result::target_outside_limits);
  EXPECT_EQ(out.error_axis, 0);
  EXPECT_EQ(out.target_excess.limit, TargetLimit::min_acceleration);
  EXPECT_NEAR(out.target_excess.by, 2.0, 1e-12);
  // Both within their bounds, but -0.5 of acceleration at 0.9 could only come from 0.9 + 0.125.
  in.target_velocity = Vector<2>{0.9, 0.0};
  in.target_acceleration = Vector<2>{-0.5, 0.0};
  in.max_velocity[0] = 1.0;
  EXPECT_EQ(Trajectory<2>::calculate(in, t, axis, nullptr, &excess), Result::target_outside_limits);
  EXPECT_EQ(excess.limit, TargetLimit::max_velocity_on_arrival);
  EXPECT_NEAR(excess.by, 0.025, 1e-12);
  EXPECT_NE(to_string(excess.limit).find("max_velocity"), std::string_view::npos);
  // The same target 0.03 lower is planned.
  in.target_velocity[0] = 0.87;
  EXPECT_EQ(Trajectory<2>::calculate(in, t, axis, nullptr, &excess), Result::working);
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

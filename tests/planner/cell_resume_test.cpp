// The cell never fails to resume (issue 23): the two ways the move executor plans from a moving
// state, over the cell's own axes (config/cell.yaml: their max speed, acceleration and jerk), each
// planned in every case of a seeded random test, optimal by the oracle and within the limits once
// braked.
// - An unhold while a hold still brakes: the SCU's soft stop takes the speed down at the axis's
//   ramp with no jerk limit (MoveExecutor::braked), so the move resumes from the acceleration bound,
//   at a speed the recipe's speed may lie below: the state must overshoot.
// - A new target while moving: from the planner's own state on the way, with the new move's speed
//   (possibly lower than the velocity it moves at).
// The move's speed is drawn from the axis's min to its max speed, so that tight limits (one ramp of
// max acceleration changes the velocity by max_accel^2 / 2 max_jerk = 2 mm/s on x, 1.5 on z, more
// than a slow move's speed range) come up as often as slow moves do.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "config/cell_core.hpp"
#include "config/yaml_node.hpp"
#include "planner/brake_oracle.hpp"
#include "planner/optimum_oracle.hpp"
#include "planner/random_problems.hpp"
#include "planner/segments_end.hpp"
#include "planner/trajectory.hpp"

namespace cellctl::planner {
namespace {

constexpr int kAxes = 2;  // x and z

std::vector<config::AxisConfig> cell_axes() {
  const config::CellCore core =
      config::parse_cell_core(config::YamlNode::load_file(CELLCTL_CELL_YAML), CELLCTL_CELL_YAML);
  return core.axes;
}

struct Move {
  Input<kAxes> input;
  std::vector<oracle::Problem> problems;  // the same, for the oracle
};

// A move of the cell's axes from `start` (position, velocity, acceleration per axis) to targets
// drawn in their travel, at a speed drawn per axis as the recipe's: what MoveExecutor::plan asks.
Move move_from(const std::vector<config::AxisConfig>& axes, const std::array<MotionState, kAxes>& start,
               std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Move m;
  for (int i = 0; i < kAxes; ++i) {
    const config::AxisConfig& a = axes[static_cast<std::size_t>(i)];
    const double speed = a.min_speed_mm_s + (a.max_speed_mm_s - a.min_speed_mm_s) * u01(rng);
    const double target = a.min_mm + (a.max_mm - a.min_mm) * u01(rng);
    const MotionState& s = start[static_cast<std::size_t>(i)];
    m.input.current_position[i] = s.position;
    m.input.current_velocity[i] = s.velocity;
    m.input.current_acceleration[i] = s.acceleration;
    m.input.target_position[i] = target;
    m.input.max_velocity[i] = speed;
    m.input.max_acceleration[i] = a.max_accel_mm_s2;
    m.input.max_jerk[i] = a.max_jerk_mm_s3;
    m.problems.push_back(
        oracle::Problem{s.position,
                        s.velocity,
                        s.acceleration,
                        target,
                        0.0,
                        0.0,
                        {speed, -speed, a.max_accel_mm_s2, -a.max_accel_mm_s2, a.max_jerk_mm_s3}});
  }
  return m;
}

std::array<MotionState, kAxes> at_rest_in_travel(const std::vector<config::AxisConfig>& axes,
                                                 std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::array<MotionState, kAxes> s{};
  for (std::size_t i = 0; i < s.size(); ++i)
    s[i].position = axes[i].min_mm + (axes[i].max_mm - axes[i].min_mm) * u01(rng);
  return s;
}

// Plans `m` and checks it: planned, optimal (the oracle brakes a start beyond the limits on its
// own), arriving, within the limits once in a state from which they can be kept. Returns the
// trajectory.
Trajectory<kAxes> expect_planned(const Move& m, const std::string& what) {
  Trajectory<kAxes> t;
  int axis = -1;
  const Result r = Trajectory<kAxes>::calculate(m.input, t, axis);
  EXPECT_EQ(r, Result::working) << what << ": " << to_string(r) << " on axis " << axis << "\n"
                                << to_string(m.input);
  if (r != Result::working) return t;
  // As in synchronisation_test.cpp: the oracle's brake end is known to about 1e-8.
  EXPECT_TRUE(oracle::confirms_min_common_duration(m.problems, t.duration(), 1e-7))
      << what << ": planned " << t.duration() << " s, the optimum is "
      << oracle::min_common_duration(m.problems, 1.01 * t.duration() + 1e-9) << "\n"
      << to_string(m.input);
  for (int i = 0; i < kAxes; ++i) {
    const JerkProfile& p = t.profile(i);
    const oracle::Limits& l = m.problems[static_cast<std::size_t>(i)].limits;
    const MotionState e = segments_end(p);
    EXPECT_NEAR(e.position, m.input.target_position[i], 1e-8 * (1.0 + std::abs(m.input.target_position[i])))
        << what;
    EXPECT_NEAR(e.velocity, 0.0, 1e-8) << what;
    bool braked = oracle::in_safe_set(p.start().velocity, p.start().acceleration, l);
    for (int k = 0; k <= 400; ++k) {
      const MotionState s = p.at(t.duration() * k / 400.0);
      if (!braked) {
        braked = oracle::in_safe_set(s.velocity, s.acceleration, l);
        continue;
      }
      EXPECT_LE(std::abs(s.velocity), l.vmax * (1.0 + 1e-9)) << what << " axis " << i << " at " << k;
      EXPECT_LE(std::abs(s.acceleration), l.amax * (1.0 + 1e-9)) << what << " axis " << i << " at " << k;
    }
  }
  return t;
}

// Seeded cases over the cell's own axes: a first move from rest, planned; `resume` turns it into the
// state a second plan starts from (drawing what it needs from the generator); that plan must succeed
// and be exact. Says how many axes had to brake first.
template <class Resume>
void resume_cases(std::uint64_t default_seed, const char* what, Resume resume) {
  const std::vector<config::AxisConfig> axes = cell_axes();
  ASSERT_GE(axes.size(), static_cast<std::size_t>(kAxes));
  const std::uint64_t seed = testing::problem_seed(default_seed);
  std::mt19937_64 rng(seed);
  const long count = testing::problem_count(20000) / 10;
  long overshooting = 0;
  for (long c = 0; c < count && !::testing::Test::HasFailure(); ++c) {
    const Move first = move_from(axes, at_rest_in_travel(axes, rng), rng);
    const Trajectory<kAxes> t = expect_planned(first, std::string("the move before ") + what);
    const Move next = move_from(axes, resume(axes, t, rng), rng);
    for (const oracle::Problem& p : next.problems) overshooting += oracle::braked(p).delay > 0.0 ? 1 : 0;
    expect_planned(next,
                   std::string(what) + " of case " + std::to_string(c) + " seed " + std::to_string(seed));
  }
  std::printf("%ld cases of %s (seed %llu), %ld axes braked first\n", count, what,
              static_cast<unsigned long long>(seed), overshooting);
}

// An unhold while the hold still brakes: the move's planned state when the hold came (its
// acceleration taken as zero, as MoveExecutor::hold does), braked at each axis's ramp for a random
// part of its stop, is where the move resumes to its targets.
TEST(CellResume, AnUnholdDuringTheBrakeIsAlwaysPlanned) {
  resume_cases(
      23, "the unhold",
      [](const std::vector<config::AxisConfig>& axes, const Trajectory<kAxes>& t, std::mt19937_64& rng) {
        std::uniform_real_distribution<double> u01(0.0, 1.0);
        const double held_at = t.duration() * u01(rng);
        std::array<MotionState, kAxes> resumed{};
        for (int i = 0; i < kAxes; ++i) {
          const MotionState s = t.profile(i).at(held_at);
          const double ramp = axes[static_cast<std::size_t>(i)].max_accel_mm_s2;
          const double stop_s = std::abs(s.velocity) / ramp;
          const double since = stop_s * u01(rng);
          const double decel = -std::copysign(ramp, s.velocity);
          resumed[static_cast<std::size_t>(i)] = {
              s.position + s.velocity * since + 0.5 * decel * since * since, s.velocity + decel * since,
              since < stop_s ? decel : 0.0};
        }
        return resumed;
      });
}

// A new target (and speed) while moving: from the planner's state at a random time of the move.
TEST(CellResume, ANewTargetWhileMovingIsAlwaysPlanned) {
  resume_cases(24, "the new target",
               [](const std::vector<config::AxisConfig>&, const Trajectory<kAxes>& t, std::mt19937_64& rng) {
                 std::uniform_real_distribution<double> u01(0.0, 1.0);
                 const double at = t.duration() * u01(rng);
                 std::array<MotionState, kAxes> moving{};
                 for (int i = 0; i < kAxes; ++i) moving[static_cast<std::size_t>(i)] = t.profile(i).at(at);
                 return moving;
               });
}

}  // namespace
}  // namespace cellctl::planner

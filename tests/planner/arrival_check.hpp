#pragma once
// The check every multi-axis planner test makes of a trajectory: each axis ends in its target
// exactly at the common duration, within its limits throughout (from the end of a brake on).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "planner/brake_oracle.hpp"
#include "planner/segments_end.hpp"
#include "planner/trajectory.hpp"

namespace cellctl::planner {

// Every axis ends in its target exactly at the common duration, within its limits throughout.
template <int N>
inline void expect_arrives_together(const Trajectory<N>& t, const Input<N>& in, const std::string& what) {
  for (int i = 0; i < N; ++i) {
    const JerkProfile& p = t.profile(i);
    EXPECT_NEAR(p.duration(), t.duration(), 1e-9 * (1.0 + t.duration())) << what << " axis " << i;
    const MotionState e = segments_end(p);
    EXPECT_NEAR(e.position, in.target_position[i], 1e-8) << what << " axis " << i;
    EXPECT_NEAR(e.velocity, in.target_velocity[i], 1e-8) << what << " axis " << i;
    EXPECT_NEAR(e.acceleration, 0.0, 1e-8) << what << " axis " << i;
    // The end the profile states (its state from then on) is where its segments lead.
    EXPECT_NEAR(p.end().position, e.position, 1e-8) << what << " axis " << i;
    EXPECT_NEAR(p.end().velocity, e.velocity, 1e-8) << what << " axis " << i;
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

}  // namespace cellctl::planner

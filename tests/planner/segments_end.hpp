#pragma once
// Where a profile's segments lead: its start integrated over every segment. A profile the planner
// builds to a target at rest has the target's state as its end without integrating its pieces
// again (AxisProfile::prepare: a blend ends in the blend of its parts' ends, which were checked), so
// the tests check that the segments themselves arrive, not the end the profile states.

#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

[[nodiscard]] inline MotionState segments_end(const JerkProfile& p) {
  MotionState s = p.start();
  for (std::size_t i = 0; i < p.size(); ++i) s = integrate(s, p.segment(i).jerk, p.segment(i).duration);
  return s;
}

}  // namespace cellctl::planner

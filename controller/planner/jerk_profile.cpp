#include "planner/jerk_profile.hpp"

#include <cassert>

namespace cellctl::planner {

MotionState integrate(const MotionState& s, double jerk, double t) noexcept {
  return MotionState{
      s.position + t * (s.velocity + t * (s.acceleration / 2.0 + t * jerk / 6.0)),
      s.velocity + t * (s.acceleration + t * jerk / 2.0),
      s.acceleration + t * jerk,
  };
}

void JerkProfile::append(JerkSegment segment) noexcept {
  if (segment.duration <= 0.0) return;
  assert(count_ < kMaxSegments);
  segments_[count_++] = segment;
  end_ = integrate(end_, segment.jerk, segment.duration);
  duration_ += segment.duration;
}

MotionState JerkProfile::at(double t) const noexcept {
  if (t <= 0.0) return start_;
  if (t >= duration_) return end_;
  MotionState s = start_;
  for (std::size_t i = 0; i < count_; ++i) {
    const JerkSegment& seg = segments_[i];
    if (t <= seg.duration) return integrate(s, seg.jerk, t);
    s = integrate(s, seg.jerk, seg.duration);
    t -= seg.duration;
  }
  return end_;
}

}  // namespace cellctl::planner

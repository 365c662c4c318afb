#include "planner/jerk_profile.hpp"

#include <cmath>

namespace cellctl::planner {

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

double JerkProfile::jerk_at(double t) const noexcept {
  if (t < 0.0 || t >= duration_) return 0.0;
  for (std::size_t i = 0; i < count_; ++i) {
    if (t < segments_[i].duration) return segments_[i].jerk;
    t -= segments_[i].duration;
  }
  return 0.0;
}

PositionExtrema JerkProfile::extrema() const noexcept {
  PositionExtrema e{{start_.position, 0.0}, {start_.position, 0.0}};
  const auto consider = [&e](double p, double t) {
    if (p < e.min.position) e.min = {p, t};
    if (p > e.max.position) e.max = {p, t};
  };
  consider(end_.position, duration_);
  MotionState s = start_;
  double t0 = 0.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const JerkSegment& seg = segments_[i];
    // Inside a segment the position has its extrema where v(t) = v + a t + j t^2 / 2 = 0.
    const double qa = seg.jerk / 2.0;
    const double qb = s.acceleration;
    const double qc = s.velocity;
    std::array<double, 2> roots{-1.0, -1.0};
    if (qa == 0.0) {
      if (qb != 0.0) roots[0] = -qc / qb;
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc >= 0.0) {
        // The form that does not cancel.
        const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
        roots[0] = q / qa;
        if (q != 0.0) roots[1] = qc / q;
      }
    }
    for (const double r : roots) {
      if (r > 0.0 && r < seg.duration) consider(integrate(s, seg.jerk, r).position, t0 + r);
    }
    s = integrate(s, seg.jerk, seg.duration);
    t0 += seg.duration;
    consider(s.position, t0);
  }
  return e;
}

}  // namespace cellctl::planner

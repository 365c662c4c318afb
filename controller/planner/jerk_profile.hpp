#pragma once
// A one-dimensional motion made of constant-jerk segments from a known start state. Every profile
// the planner builds (a brake, a time-optimal profile, a profile stretched to a common duration)
// is stored in this one form, so one evaluation function integrates them all and there is a single
// place where the physics lives. Fixed-size storage: building and evaluating never allocate.

#include <array>
#include <cstddef>

namespace cellctl::planner {

struct MotionState {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

struct JerkSegment {
  double jerk = 0.0;
  double duration = 0.0;
};

// The state reached from `s` after `t` seconds at constant jerk `jerk`.
[[nodiscard]] MotionState integrate(const MotionState& s, double jerk, double t) noexcept;

// Where a position extremum of a profile is, and when.
struct PositionExtremum {
  double position = 0.0;
  double time = 0.0;
};

struct PositionExtrema {
  PositionExtremum min;
  PositionExtremum max;
};

class JerkProfile {
 public:
  // The longest profile: a brake (3 segments) then a blend of two 7-segment extreme profiles,
  // whose merged switching times give at most 13 segments.
  static constexpr std::size_t kMaxSegments = 16;

  JerkProfile() = default;
  explicit JerkProfile(const MotionState& start) noexcept : start_(start), end_(start) {}

  // Adds a segment after the last one; zero-length segments are dropped. Precondition: fewer than
  // kMaxSegments segments so far (the shapes are built by code that knows their length).
  void append(JerkSegment segment) noexcept;

  [[nodiscard]] const MotionState& start() const noexcept { return start_; }
  [[nodiscard]] const MotionState& end() const noexcept { return end_; }
  [[nodiscard]] double duration() const noexcept { return duration_; }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] const JerkSegment& segment(std::size_t i) const noexcept { return segments_[i]; }

  // The state at time t since the start; before 0 the start state, after duration() the end state
  // (the target state, which the planner holds).
  [[nodiscard]] MotionState at(double t) const noexcept;
  // The jerk at time t (0 outside the profile).
  [[nodiscard]] double jerk_at(double t) const noexcept;
  // The lowest and highest position over the whole profile, with their times (overshoot included).
  [[nodiscard]] PositionExtrema extrema() const noexcept;

 private:
  MotionState start_;
  MotionState end_;
  std::array<JerkSegment, kMaxSegments> segments_{};
  std::size_t count_ = 0;
  double duration_ = 0.0;
};

}  // namespace cellctl::planner

#pragma once
// A one-dimensional motion made of constant-jerk segments from a known start state. Every profile
// the planner builds (a 7-segment S-curve, a jerk-limited stop) is stored in this one form, so one
// evaluation function integrates them all and there is a single place where the physics lives.

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

class JerkProfile {
 public:
  // Seven is the longest shape built here (the S-curve); a stop needs three.
  static constexpr std::size_t kMaxSegments = 7;

  JerkProfile() = default;
  explicit JerkProfile(const MotionState& start) noexcept : start_(start), end_(start) {}

  // Adds a segment after the last one; zero-length segments are dropped. Precondition: fewer than
  // kMaxSegments segments so far (the shapes are built by code that knows their length).
  void append(JerkSegment segment) noexcept;

  [[nodiscard]] const MotionState& start() const noexcept { return start_; }
  [[nodiscard]] const MotionState& end() const noexcept { return end_; }
  [[nodiscard]] double duration() const noexcept { return duration_; }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }

  // The state at time t since the start; before 0 the start state, after duration() the end state
  // (every profile built here ends at rest, so holding the end state is the physical continuation).
  [[nodiscard]] MotionState at(double t) const noexcept;

 private:
  MotionState start_;
  MotionState end_;
  std::array<JerkSegment, kMaxSegments> segments_{};
  std::size_t count_ = 0;
  double duration_ = 0.0;
};

}  // namespace cellctl::planner

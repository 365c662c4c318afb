#pragma once
// The jerk-limited, time-synchronised trajectory planner, in the shape of ruckig's examples:
//
//   Planner<3> planner(0.001);
//   Input<3> in; ... Output<3> out;
//   while (planner.update(in, out) == Result::working) { send(out.new_position); out.pass_to_input(in); }
//
// Choices (why):
// - Coordinated straight-line moves. From rest, every enabled axis follows p_i = start_i + d_i s(t)
//   with one scalar S-curve s: 0 -> 1 whose limits are the tightest of max_i / |d_i|. Hence all axes
//   start and arrive together, the slowest axis sets the duration, the others are stretched, and
//   the path is a straight line in joint space (the normalised progress of every axis is s).
// - A new target (or limits, or mask) while moving: every moving axis first stops on its own
//   time-optimal jerk-limited brake, the axes wait for the slowest brake, then the straight-line
//   move to the new target starts from rest. Position, velocity and acceleration stay continuous
//   and within the limits; the stop costs time against a time-optimal blend, which we accept for
//   a profile that is simple to prove safe.
// - The planner replans whenever the Input differs from the one it continued last time. Feed the
//   output back with Output::pass_to_input (open-loop, like ruckig); feeding measured states every
//   cycle would restart the profile every cycle.
// - Disabled axes are not planned: their output is their current input state.
// - Pure: no clock (time is steps x dt), no I/O, no allocation (fixed-size Eigen vectors, N <= 6).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "planner/jerk_profile.hpp"
#include "planner/profile_shapes.hpp"
#include "planner/result.hpp"

namespace cellctl::planner {

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

// Eigen sizes are int, std::array sizes are size_t.
template <int N>
using AxisArray = std::array<bool, static_cast<std::size_t>(N)>;

template <int N>
struct Input {
  Vector<N> current_position = Vector<N>::Zero();
  Vector<N> current_velocity = Vector<N>::Zero();
  Vector<N> current_acceleration = Vector<N>::Zero();
  Vector<N> target_position = Vector<N>::Zero();
  Vector<N> max_velocity = Vector<N>::Ones();
  Vector<N> max_acceleration = Vector<N>::Ones();
  Vector<N> max_jerk = Vector<N>::Ones();
  AxisArray<N> enabled = filled(true);

  friend bool operator==(const Input& a, const Input& b) noexcept {
    return a.current_position == b.current_position && a.current_velocity == b.current_velocity &&
           a.current_acceleration == b.current_acceleration && a.target_position == b.target_position &&
           a.max_velocity == b.max_velocity && a.max_acceleration == b.max_acceleration &&
           a.max_jerk == b.max_jerk && a.enabled == b.enabled;
  }

 private:
  static constexpr AxisArray<N> filled(bool value) noexcept {
    AxisArray<N> a{};
    a.fill(value);
    return a;
  }
};

template <int N>
struct Output {
  Vector<N> new_position = Vector<N>::Zero();
  Vector<N> new_velocity = Vector<N>::Zero();
  Vector<N> new_acceleration = Vector<N>::Zero();
  double time = 0.0;      // of the new state, since the current profile was planned [s]
  double duration = 0.0;  // of the whole current profile, a stop before the move included [s]
  bool done = false;      // the new state is the target, at rest
  int error_axis = -1;    // the axis named by an error Result, -1 otherwise

  // The new state becomes the next current state: the normal way to step the planner.
  void pass_to_input(Input<N>& in) const noexcept {
    in.current_position = new_position;
    in.current_velocity = new_velocity;
    in.current_acceleration = new_acceleration;
  }
};

template <int N>
class Planner {
  static_assert(N >= 1 && N <= 6, "the cell has one to six axes");

 public:
  // dt: the control cycle [s]; throws std::invalid_argument unless finite and > 0 (config time).
  explicit Planner(double dt) : dt_(dt) {
    if (!std::isfinite(dt) || dt <= 0.0) {
      throw std::invalid_argument("planner: dt must be finite and > 0, got " + std::to_string(dt));
    }
  }

  [[nodiscard]] double dt() const noexcept { return dt_; }

  // One cycle: the state dt after the current one. Replans when `in` is not the continuation of the
  // previous call (see the choices above). On an error, `out` keeps its state and names the axis.
  [[nodiscard]] Result update(const Input<N>& in, Output<N>& out) noexcept {
    out.error_axis = -1;
    if (const Result r = validate(in, out.error_axis); is_error(r)) return r;
    if (!planned_ || !(in == continued_)) plan(in);
    if (step_ < kHoldStep) ++step_;
    evaluate(in, out);
    continued_ = in;
    out.pass_to_input(continued_);
    return out.done ? Result::finished : Result::working;
  }

 private:
  // Once past the end, the step count stops growing (a finished planner may be polled forever).
  static constexpr std::int64_t kHoldStep = std::int64_t{1} << 52;

  static Result validate(const Input<N>& in, int& axis) noexcept {
    for (int i = 0; i < N; ++i) {
      if (!in.enabled[static_cast<std::size_t>(i)]) continue;
      axis = i;
      if (!std::isfinite(in.current_position[i]) || !std::isfinite(in.current_velocity[i]) ||
          !std::isfinite(in.current_acceleration[i]) || !std::isfinite(in.target_position[i])) {
        return Result::invalid_state;
      }
      const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
      if (!positive(in.max_velocity[i]) || !positive(in.max_acceleration[i]) || !positive(in.max_jerk[i])) {
        return Result::invalid_limits;
      }
    }
    axis = -1;
    return Result::working;
  }

  static AxisLimits limits_of(const Input<N>& in, int i) noexcept {
    return AxisLimits{in.max_velocity[i], in.max_acceleration[i], in.max_jerk[i]};
  }

  void plan(const Input<N>& in) noexcept {
    planned_ = true;
    step_ = 0;
    brake_duration_ = 0.0;
    // The scalar path s: 0 -> 1 moves axis i by move_[i]; its limits are the tightest per-axis ones.
    constexpr double kNone = std::numeric_limits<double>::infinity();
    AxisLimits path_limits{kNone, kNone, kNone};
    bool any_move = false;
    for (int i = 0; i < N; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (!in.enabled[k]) continue;
      const MotionState now{in.current_position[i], in.current_velocity[i], in.current_acceleration[i]};
      const bool at_rest = now.velocity == 0.0 && now.acceleration == 0.0;
      brakes_[k] = at_rest ? JerkProfile(now) : brake_to_rest(now, limits_of(in, i));
      brake_duration_ = std::max(brake_duration_, brakes_[k].duration());
      path_start_[i] = brakes_[k].end().position;
      move_[i] = in.target_position[i] - path_start_[i];
      if (move_[i] == 0.0) continue;
      any_move = true;
      const double d = std::abs(move_[i]);
      path_limits.velocity = std::min(path_limits.velocity, in.max_velocity[i] / d);
      path_limits.acceleration = std::min(path_limits.acceleration, in.max_acceleration[i] / d);
      path_limits.jerk = std::min(path_limits.jerk, in.max_jerk[i] / d);
    }
    path_ = any_move ? rest_to_rest(1.0, path_limits) : JerkProfile(MotionState{});
    duration_ = brake_duration_ + path_.duration();
  }

  void evaluate(const Input<N>& in, Output<N>& out) const noexcept {
    const double t = static_cast<double>(step_) * dt_;
    out.duration = duration_;
    out.time = std::min(t, duration_);
    out.done = t >= duration_;
    const MotionState s = path_.at(t - brake_duration_);
    for (int i = 0; i < N; ++i) {
      const auto k = static_cast<std::size_t>(i);
      MotionState axis{in.current_position[i], in.current_velocity[i], in.current_acceleration[i]};
      if (in.enabled[k]) {
        if (out.done) {
          axis = MotionState{in.target_position[i], 0.0, 0.0};  // exact arrival, no rounding residue
        } else if (t < brake_duration_) {
          axis = brakes_[k].at(t);
        } else {
          axis = MotionState{path_start_[i] + move_[i] * s.position, move_[i] * s.velocity,
                             move_[i] * s.acceleration};
        }
      }
      out.new_position[i] = axis.position;
      out.new_velocity[i] = axis.velocity;
      out.new_acceleration[i] = axis.acceleration;
    }
  }

  double dt_;
  bool planned_ = false;
  Input<N> continued_;
  std::int64_t step_ = 0;
  std::array<JerkProfile, static_cast<std::size_t>(N)> brakes_{};
  double brake_duration_ = 0.0;
  Vector<N> path_start_ = Vector<N>::Zero();
  Vector<N> move_ = Vector<N>::Zero();
  JerkProfile path_;
  double duration_ = 0.0;
};

}  // namespace cellctl::planner

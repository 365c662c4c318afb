#pragma once
// The jerk-limited, time-optimal trajectory planner for N axes, stepped at the control cycle:
//
//   Planner<3> planner(0.001);
//   Input<3> in; ... Output<3> out;
//   while (planner.update(in, out) == Result::working) { send(out.new_position); out.pass_to_input(in); }
//
// Choices (why):
// - From any state: each axis gets its time-optimal third-order profile from its current position,
//   velocity and acceleration (a brake first only if it is beyond its limits), so a new target,
//   a correction or an unhold from a moving state costs no stop (see axis_profile.hpp).
// - Synchronisation as the Input asks (see trajectory.hpp): time by default, phase for a
//   straight line, none for independent axes.
// - The planner replans whenever the Input differs from the one it continued last time. Feed the
//   output back with Output::pass_to_input (open-loop); feeding measured states every cycle would
//   restart the profile every cycle.
// - Disabled axes are not planned: their output is their current input state.
// - Pure: no clock (time is steps x dt), no I/O, no allocation (fixed-size storage, N <= 6).

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "planner/input.hpp"
#include "planner/result.hpp"
#include "planner/trajectory.hpp"

namespace cellctl::planner {

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
  // The trajectory being followed (valid once update() has planned one).
  [[nodiscard]] const Trajectory<N>& trajectory() const noexcept { return trajectory_; }

  // One cycle: the state dt after the current one. Replans when `in` is not the continuation of the
  // previous call. On an error, `out` keeps its state and names the axis; the previous trajectory
  // (if any) is kept but not continued.
  [[nodiscard]] Result update(const Input<N>& in, Output<N>& out) noexcept {
    out.new_calculation = false;
    out.travel_excess = {};
    out.target_excess = {};
    if (!planned_ || !(in == continued_)) {
      const Result r =
          Trajectory<N>::calculate(in, trajectory_, out.error_axis, &out.travel_excess, &out.target_excess);
      if (is_error(r)) {
        planned_ = false;
        return r;
      }
      planned_ = true;
      step_ = 0;
      out.new_calculation = true;
    }
    out.error_axis = -1;
    if (step_ < kHoldStep) ++step_;
    evaluate(in, out);
    continued_ = in;
    out.pass_to_input(continued_);
    return out.done ? Result::finished : Result::working;
  }

 private:
  // Once past the end, the step count stops growing (a finished planner may be polled forever).
  static constexpr std::int64_t kHoldStep = std::int64_t{1} << 52;

  void evaluate(const Input<N>& in, Output<N>& out) const noexcept {
    const double t = static_cast<double>(step_) * dt_;
    const double duration = trajectory_.duration();
    out.duration = duration;
    out.time = std::min(t, duration);
    out.done = t >= duration;
    out.note = trajectory_.note();
    out.new_position = in.current_position;
    out.new_velocity = in.current_velocity;
    out.new_acceleration = in.current_acceleration;
    out.new_jerk.setZero();
    trajectory_.at_time(t, out.new_position, out.new_velocity, out.new_acceleration, out.new_jerk);
    if (!out.done) return;
    for (int i = 0; i < N; ++i) {  // exact arrival, no rounding residue
      if (!in.enabled[static_cast<std::size_t>(i)]) continue;
      out.new_position[i] = in.target_position[i];
      out.new_velocity[i] = in.target_velocity[i];
      out.new_acceleration[i] = in.target_acceleration[i];
    }
  }

  double dt_;
  bool planned_ = false;
  Input<N> continued_;
  std::int64_t step_ = 0;
  Trajectory<N> trajectory_;
};

}  // namespace cellctl::planner

#pragma once
// The physics of one linear actuator, as the emulated SCU drives it: travel between 0 (fully in) and
// the stroke, speed with soft (ramped) or fast start/stop, a minimum speed below which the motor
// does not move at all, and a position sensor that may read a little wrong (scale error), which is
// what the cell's encoder exists to catch. Positions here are in the actuator's own sensor frame
// ("indicated" mm, what the SCU counts); true_position_mm() is where the rod really is.

#include "link/clock.hpp"

namespace cellctl::plant {

struct ActuatorParams {
  double stroke_mm = 200.0;
  double max_speed_mm_s = 20.0;  // at 100 % speed
  double ramp_mm_s2 = 40.0;      // soft start/stop acceleration
  double min_speed_mm_s = 0.8;   // below this the motor stalls (threshold depends on actuator and load)
  double start_position_mm = 0.0;
  double scale_error = 0.0;  // indicated = true × (1 + scale_error)
};

class Actuator {
 public:
  explicit Actuator(const ActuatorParams& params) noexcept;

  // Moves toward target (indicated mm, clamped to the stroke) at speed; soft ramps, fast jumps.
  void move_to(double target_mm, double speed_mm_s, bool soft) noexcept;
  // Changes the cruise speed during a motion, keeping the ramp.
  void set_speed(double speed_mm_s) noexcept;
  void stop(bool soft) noexcept;
  void step(link::Duration dt) noexcept;

  // Fault injection: a blocked actuator (mechanical jam) does not move whatever it is told.
  void set_blocked(bool blocked) noexcept { blocked_ = blocked; }
  // A plant change at run time, for closed-loop tests.
  void set_scale_error(double e) noexcept { params_.scale_error = e; }

  [[nodiscard]] double position_mm() const noexcept { return position_; }
  [[nodiscard]] double true_position_mm() const noexcept { return position_ / (1.0 + params_.scale_error); }
  [[nodiscard]] double velocity_mm_s() const noexcept { return velocity_; }
  [[nodiscard]] bool moving() const noexcept { return velocity_ != 0.0; }
  // Commanded to move, but the speed is below the motor's threshold (or it is blocked): no motion.
  [[nodiscard]] bool stalled() const noexcept { return active_ && velocity_ == 0.0 && !can_move(); }
  // A motion command is in force (not yet stopped or arrived).
  [[nodiscard]] bool active() const noexcept { return active_; }
  [[nodiscard]] bool at_in_limit() const noexcept { return position_ <= 0.0; }
  [[nodiscard]] bool at_out_limit() const noexcept { return position_ >= params_.stroke_mm; }
  [[nodiscard]] const ActuatorParams& params() const noexcept { return params_; }

 private:
  [[nodiscard]] bool can_move() const noexcept { return !blocked_ && speed_ >= params_.min_speed_mm_s; }

  ActuatorParams params_;
  double position_;
  double velocity_ = 0.0;  // signed, mm/s
  double target_ = 0.0;
  double speed_ = 0.0;  // commanded cruise speed, unsigned
  bool soft_ = true;
  bool active_ = false;
  bool stopping_ = false;
  bool blocked_ = false;
};

}  // namespace cellctl::plant

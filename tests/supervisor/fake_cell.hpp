#pragma once
// A cell without its protocols, for testing the supervisor alone: intents drive the plant models
// (the same ones the emulators use) directly, and the plant is read back as a CellState. The SCU
// reports the actuator's indicated position, the encoder the true one. The SCU's motion bit can be
// made to lag a move command (set_motion_latency), as the real one does until its next RC reply.

#include <vector>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_config.hpp"
#include "plant/actuator.hpp"
#include "plant/spindle_motor.hpp"

namespace cellctl::testing {

class FakeCell {
 public:
  explicit FakeCell(const config::CellConfig& cell, double scale_error = 0.0, double min_speed_mm_s = 0.5)
      : cell_(cell), spindle_({.ramp_up_hz_s = 800, .ramp_down_hz_s = 800}) {
    for (const auto& a : cell.axes)
      actuators_.emplace_back(plant::ActuatorParams{.stroke_mm = a.max_mm,
                                                    .max_speed_mm_s = a.max_speed_mm_s,
                                                    .ramp_mm_s2 = a.max_accel_mm_s2,
                                                    .min_speed_mm_s = min_speed_mm_s,
                                                    .start_position_mm = 0.0,
                                                    .scale_error = scale_error});
    ids_.resize(actuators_.size(), 0);
    motion_reported_from_.resize(actuators_.size(), link::Duration{});
  }

  // A move's motion is reported this long after it was commanded (the real SCU's status comes with
  // its RC reply, up to one keep-alive period later); before that the axis reads as not moving.
  void set_motion_latency(link::Duration latency) { motion_latency_ = latency; }

  void apply(const cell::Intents& in) {
    for (std::size_t i = 0; i < actuators_.size(); ++i) {
      auto& act = actuators_[i];
      const auto& intent = in.axes[i];
      if (in.halt == cell::Halt::immediate) {
        act.stop(false);
        continue;
      }
      if (in.halt == cell::Halt::controlled || !intent.move) {
        if (act.active()) act.stop(true);
        continue;
      }
      if (intent.move_id != ids_[i]) {
        ids_[i] = intent.move_id;
        act.move_to(intent.target_mm, intent.speed_mm_s, intent.soft);
        motion_reported_from_[i] = elapsed_ + motion_latency_;
      } else {
        act.set_speed(intent.speed_mm_s);
      }
    }
    if (in.spindle.run && in.halt == cell::Halt::none)
      spindle_.run(in.spindle.frequency_hz, in.spindle.clockwise);
    else
      spindle_.stop();
    spindle_set_ = in.spindle.run ? in.spindle.frequency_hz : 0.0;
  }

  void advance(link::Duration dt) {
    elapsed_ += dt;
    for (auto& a : actuators_) a.step(dt);
    spindle_.step(dt);
  }

  [[nodiscard]] cell::CellState state(link::TimePoint now) const {
    cell::CellState s;
    s.now = now;
    s.axis_count = static_cast<std::uint8_t>(actuators_.size());
    for (std::size_t i = 0; i < actuators_.size(); ++i) {
      auto& a = s.axes[i];
      a.present = true;
      a.scu_mm = actuators_[i].position_mm();
      a.moving = actuators_[i].moving() && elapsed_ >= motion_reported_from_[i];
      // The move stays open until the SCU has reported it and the actuator has come to its end.
      a.commanded = ids_[i] != 0 && (elapsed_ < motion_reported_from_[i] || actuators_[i].active());
      a.homed = true;
      a.measured = cell_.axes[i].encoder;
      if (a.measured) {
        a.encoder_mm = actuators_[i].true_position_mm();
        a.encoder_mm_s = actuators_[i].velocity_mm_s() / (1.0 + actuators_[i].params().scale_error);
        s.encoder.mm = a.encoder_mm;
      }
    }
    s.encoder.data_exchange = s.encoder.ready = true;
    s.spindle.active = true;
    s.spindle.actual_hz = spindle_.frequency_hz();
    s.spindle.set_hz = spindle_set_;
    s.spindle.at_rest = spindle_.at_rest();
    s.spindle.at_speed = spindle_set_ > 0 && std::abs(std::abs(spindle_.frequency_hz()) - spindle_set_) < 1.0;
    for (auto& l : s.links) l.active = true;
    s.scu_remote = true;
    s.scu_status2_known = true;
    return s;
  }

  std::vector<plant::Actuator>& actuators() { return actuators_; }

 private:
  const config::CellConfig& cell_;
  std::vector<plant::Actuator> actuators_;
  std::vector<std::uint32_t> ids_;
  link::Duration motion_latency_{};
  link::Duration elapsed_{};                          // advanced so far
  std::vector<link::Duration> motion_reported_from_;  // by axis: when its motion bit catches up
  plant::SpindleMotor spindle_;
  double spindle_set_ = 0.0;
};

}  // namespace cellctl::testing

#pragma once
// A cell without its protocols, for testing the supervisor alone: intents drive the plant models
// (the same ones the emulators use) directly, and the plant is read back as a CellState. The SCU
// reports the actuator's indicated position, the encoder the true one. The SCU's motion bit can be
// made to lag a move command (set_motion_latency), as the real one does until its next RC reply.
// Like the real devices: a category-0 stop halts an axis in the cycle after it was decided (the F20
// is on the line in cycle k, the SCU acts on it after), a controlled hold keeps the spindle running,
// and "initialised" is known only once the SCU's status 2 has been read (set_status2_after). As the
// SCU (and its emulator) does, an actuator is not initialised at power-up and becomes initialised when
// a run brings it into its retracted end (set_scu_initialised says it already is); the end bits ("in"/"out
// position") follow the plant, and the encoder takes a preset (Intents::encoder) a few cycles after it
// is asked for. The failure branches can be produced on purpose: an axis not homed, a refused move,
// a refused start.

#include <algorithm>
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
    scu_initialised_.resize(actuators_.size(), false);
    refuses_moves_.resize(actuators_.size(), false);
    move_refused_.resize(actuators_.size(), false);
    moves_taken_.resize(actuators_.size(), 0);
    fast_stop_due_.resize(actuators_.size(), false);
  }

  // Actuator status 2 is known from this time on (the real session reads it after the first refresh);
  // Duration::max(): never.
  void set_status2_after(link::Duration d) { status2_after_ = d; }
  void set_scu_initialised(std::size_t axis, bool initialised) { scu_initialised_.at(axis) = initialised; }
  // The SCU answers an error to the axis's next moves: the actuator does not move, the move reads refused.
  void refuse_moves(std::size_t axis) { refuses_moves_.at(axis) = true; }
  // The converter acknowledges starts but stays at rest, with this warning/fault number.
  void refuse_spindle_start(std::uint8_t error_number) { spindle_refusal_ = error_number; }

  // A move's motion is reported this long after it was commanded (the real SCU's status comes with
  // its RC reply, up to one keep-alive period later); before that the axis reads as not moving.
  void set_motion_latency(link::Duration latency) { motion_latency_ = latency; }

  void apply(const cell::Intents& in) {
    for (std::size_t i = 0; i < actuators_.size(); ++i) {
      auto& act = actuators_[i];
      const auto& intent = in.axes[i];
      if (in.halt == cell::Halt::immediate) {
        fast_stop_due_[i] = act.active();  // at the end of this cycle, not in it
        continue;
      }
      if (in.halt == cell::Halt::controlled || !intent.move) {
        if (act.active()) act.stop(true);
        continue;
      }
      if (intent.move_id != ids_[i]) {
        ids_[i] = intent.move_id;
        move_refused_[i] = refuses_moves_[i];
        if (move_refused_[i]) continue;
        act.move_to(intent.target_mm, intent.speed_mm_s, intent.soft);
        ++moves_taken_[i];  // the RE answered at once
        motion_reported_from_[i] = elapsed_ + motion_latency_;
      } else {
        act.set_speed(intent.speed_mm_s);
      }
    }
    // A controlled hold keeps the spindle running (CellDevices stops it only on category 0).
    if (in.spindle.run && in.halt != cell::Halt::immediate && !spindle_refusal_)
      spindle_.run(in.spindle.frequency_hz, in.spindle.clockwise);
    else
      spindle_.stop();
    spindle_set_ = in.spindle.run ? in.spindle.frequency_hz : 0.0;
    if (in.encoder.preset_id != preset_id_) {
      preset_id_ = in.encoder.preset_id;
      preset_mm_ = in.encoder.preset_mm;
      preset_due_ = elapsed_ + std::chrono::milliseconds(10);  // the handshake takes a few exchanges
    }
  }

  void advance(link::Duration dt) {
    elapsed_ += dt;
    for (std::size_t i = 0; i < actuators_.size(); ++i) {
      const double before = actuators_[i].position_mm();
      actuators_[i].step(dt);
      if (actuators_[i].at_in_limit() && before > 0.0)
        scu_initialised_[i] = true;  // run into the retracted end
      if (fast_stop_due_[i]) actuators_[i].stop(false);
      fast_stop_due_[i] = false;
    }
    spindle_.step(dt);
    if (preset_id_ != 0 && preset_done_id_ != preset_id_ && elapsed_ >= preset_due_) {
      for (std::size_t i = 0; i < actuators_.size(); ++i)
        if (cell_.axes[i].encoder) encoder_offset_mm_ = preset_mm_ - actuators_[i].true_position_mm();
      preset_done_id_ = preset_id_;
    }
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
      a.scu_initialised =
          scu_initialised_[i] && elapsed_ >= status2_after_;  // unknown reads as not initialised
      a.at_retracted_end = actuators_[i].at_in_limit();
      a.at_extended_end = actuators_[i].at_out_limit();
      a.move_refused = move_refused_[i];
      a.moves_taken = moves_taken_[i];
      a.measured = cell_.axes[i].encoder;
      if (a.measured) {
        a.encoder_mm = actuators_[i].true_position_mm() + encoder_offset_mm_;
        a.encoder_mm_s = actuators_[i].velocity_mm_s() / (1.0 + actuators_[i].params().scale_error);
        s.encoder.mm = a.encoder_mm;
      }
    }
    s.encoder.data_exchange = s.encoder.ready = true;
    s.encoder.preset_id = preset_id_;
    s.encoder.preset_done = preset_id_ != 0 && preset_done_id_ == preset_id_;
    s.spindle.active = true;
    s.spindle.actual_hz = spindle_.frequency_hz();
    s.spindle.set_hz = spindle_set_;
    s.spindle.at_rest = spindle_.at_rest();
    s.spindle.at_speed = spindle_set_ > 0 && std::abs(std::abs(spindle_.frequency_hz()) - spindle_set_) < 1.0;
    s.spindle.start_refused = spindle_set_ > 0 && spindle_refusal_ != 0;
    s.spindle.error_number = spindle_refusal_;
    for (auto& l : s.links) l.active = true;
    s.devices = {"scu", "spindle", "encoder"};
    s.scu_remote = true;
    s.scu_status2_known = elapsed_ >= status2_after_;
    if (std::find(move_refused_.begin(), move_refused_.end(), true) != move_refused_.end())
      s.scu_refusal = "PE (permission error)";
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
  link::Duration status2_after_ = std::chrono::milliseconds(30);  // about the real session's first RG
  std::vector<bool> scu_initialised_, refuses_moves_, move_refused_, fast_stop_due_;
  std::vector<std::uint32_t> moves_taken_;  // REs taken per axis
  std::uint8_t spindle_refusal_ = 0;
  std::uint32_t preset_id_ = 0, preset_done_id_ = 0;
  double preset_mm_ = 0.0;
  link::Duration preset_due_{};
  double encoder_offset_mm_ = 0.0;  // the encoder's preset offset against the axis's true position
};

}  // namespace cellctl::testing

// scu::Emulator: the motion functions and the actuators they drive — RE starts a function (or switches
// an output, the buzzer, a LED, the emergency stop F20), RS stops it; a function's target and speed;
// the plant stepped between polls.
#include <algorithm>
#include <cmath>

#include "scu/emulator.hpp"

namespace cellctl::scu {
namespace {

// The plant is integrated in steps of at most this, whatever the poll rate, so ramps stay accurate.
constexpr link::Duration kMaxPlantStep = std::chrono::milliseconds(1);

}  // namespace

void Emulator::step_plant(link::Duration dt) {
  while (dt > link::Duration::zero()) {
    const auto h = std::min(dt, kMaxPlantStep);
    for (std::size_t a = 0; a < actuators_.size(); ++a) {
      if (!config_.actuators[a].present) continue;
      const double before = actuators_[a].position_mm();
      actuators_[a].step(h);
      stroke_edges_[a] += std::abs(actuators_[a].position_mm() - before) * config_.actuators[a].edges_per_mm;
      // Our reading of the silent manual: an actuator is initialised by a run into its retracted end.
      if (actuators_[a].at_in_limit() && before > 0.0) initialised_[a] = true;
      if (!actuators_[a].active()) owner_[a] = -1;
    }
    dt -= h;
  }
}

Status Emulator::handle(const ExecuteRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  if (r.function < kMotionFunctionCount) {
    const auto& fn = config_.functions[r.function];
    if (!fn.defined || r.direction > static_cast<std::uint8_t>(Direction::remote_position))
      return Status::parameter_data_error;
    if (r.start_stop != kFastStartStop && r.start_stop != kSoftStartStop && r.start_stop != kUnusedParam)
      return Status::parameter_data_error;
    if (emergency_stop_) return Status::permission_error;  // F20 holds until its RS
    if (config_.refuses_execute_while_moving) {
      for (std::size_t a = 0; a < actuators_.size(); ++a)
        if (fn.moves(static_cast<int>(a) + 1) && actuators_[a].moving()) return Status::permission_error;
    }
    running_[r.function] = true;
    const auto d = static_cast<Direction>(r.direction);
    if (d != Direction::none) start_function(r.function, d, r.start_stop != kFastStartStop);
    return Status::ack;
  }
  switch (r.function) {
    case kEmergencyStopFnc:
      emergency_stop_ = true;
      stop_all(false);
      return Status::ack;
    case kBuzzerFnc:
      buzzer_ = 1;
      return Status::ack;
    case kBinaryOutput1Fnc:
      outputs_ |= 0x01;
      return Status::ack;
    case kBinaryOutput2Fnc:
      outputs_ |= 0x02;
      return Status::ack;
    case kLed1Fnc:
      hand_switch_leds_ |= 0x01;
      return Status::ack;
    case kLed2Fnc:
      hand_switch_leds_ |= 0x02;
      return Status::ack;
    default:
      return Status::parameter_data_error;
  }
}

Status Emulator::handle(const StopRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  if (r.mode != kFastStartStop && r.mode != kSoftStartStop && r.mode != kUnusedParam)
    return Status::parameter_data_error;
  if (r.function < kMotionFunctionCount) {
    if (!config_.functions[r.function].defined) return Status::parameter_data_error;
    stop_function(r.function, r.mode != kFastStartStop);
    running_[r.function] = false;
    return Status::ack;
  }
  switch (r.function) {
    case kEmergencyStopFnc:
      emergency_stop_ = false;
      return Status::ack;
    case kBuzzerFnc:
      buzzer_ = 0;
      return Status::ack;
    case kBinaryOutput1Fnc:
      outputs_ &= 0xFE;
      return Status::ack;
    case kBinaryOutput2Fnc:
      outputs_ &= 0xFD;
      return Status::ack;
    case kLed1Fnc:
      hand_switch_leds_ &= 0xFE;
      return Status::ack;
    case kLed2Fnc:
      hand_switch_leds_ &= 0xFD;
      return Status::ack;
    default:
      return Status::parameter_data_error;
  }
}

double Emulator::target_mm(std::size_t a, Direction d) const {
  const double stroke = config_.actuators[a].physics.stroke_mm;
  switch (d) {
    case Direction::none:
      return actuators_[a].position_mm();
    case Direction::in:
      return 0.0;
    case Direction::out:
      return stroke;
    case Direction::memory1:
    case Direction::memory2:
    case Direction::memory3:
    case Direction::memory4:
    case Direction::intermediate_in:
    case Direction::intermediate_out:
      return kUserPositionFractions[static_cast<std::size_t>(d) -
                                    static_cast<std::size_t>(Direction::memory1)] *
             stroke;
    case Direction::remote_position:
      return remote_position_[a] / config_.actuators[a].edges_per_mm;
  }
  return actuators_[a].position_mm();
}

void Emulator::start_function(std::size_t f, Direction d, bool soft) {
  const auto& fn = config_.functions[f];
  // Bits 14..21 are reset with the next motion.
  for (int bit = error_bit::kTotalCurrent; bit <= error_bit::kPositionDifference; ++bit)
    error_codes_[0] &= ~ErrorWord::mask(bit);
  // A synchronized run goes at the pace of the slowest actuator, so that all keep together.
  double max_speed = 1e300;
  for (int a = 1; a <= kActuatorCount; ++a)
    if (fn.moves(a)) max_speed = std::min(max_speed, config_.actuators[index(a)].physics.max_speed_mm_s);
  for (int a = 1; a <= kActuatorCount; ++a) {
    if (!fn.moves(a)) continue;
    const auto i = index(a);
    const double pct = remote_speed_[f] / 100.0;
    const double speed = pct * (fn.synchronized ? max_speed : config_.actuators[i].physics.max_speed_mm_s);
    const double target = target_mm(i, d);
    (target >= actuators_[i].position_mm() ? relay_out_[i] : relay_in_[i]) += 1;
    actuators_[i].move_to(target, speed, soft);
    owner_[i] = static_cast<int>(f);
    if (lasting_fault_[i]) inject_actuator_fault(a);
  }
}

void Emulator::stop_function(std::size_t f, bool soft) {
  for (std::size_t a = 0; a < actuators_.size(); ++a) {
    if (owner_[a] != static_cast<int>(f)) continue;
    actuators_[a].stop(soft);
  }
}

void Emulator::stop_all(bool soft) {
  for (std::size_t a = 0; a < actuators_.size(); ++a)
    if (config_.actuators[a].present) actuators_[a].stop(soft);
}

}  // namespace cellctl::scu

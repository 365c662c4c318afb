// scu::Emulator: the error word and its history (0x00D1..D5), the actuator, over-current and
// synchronisation faults a test injects, and a power cycle.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "scu/emulator.hpp"

namespace cellctl::scu {

void Emulator::power_cycle() {
  stop_all(false);
  initialised_ = {};  // lost whatever the emulator started with (EmulatorConfig::initialised)
  remote_open_ = rc_seen_ = lapsed_ = false;
  running_ = {};
  owner_.fill(-1);
  emergency_stop_ = false;
  remote_speed_.fill(config_.default_speed_percent);
}

void Emulator::raise_error(int bit) {
  auto& latest = error_codes_[0];
  if ((latest & ErrorWord::mask(bit)) != 0) return;
  // A new error: the word as it was moves into the history (0x00D2..D5) before the bit is added.
  if (latest != 0) {
    std::copy_backward(error_codes_.begin(), error_codes_.end() - 1, error_codes_.end());
  }
  latest |= ErrorWord::mask(bit);
}

void Emulator::inject_actuator_fault(int a) {
  const auto i = present_index(a);
  raise_error(error_bit::actuator_fault(a));
  ++actuator_errors_[i];
  actuators_[i].stop(false);
}

void Emulator::set_actuator_fault(int a, bool on) {
  lasting_fault_[present_index(a)] = on;
  if (on) inject_actuator_fault(a);
}

void Emulator::inject_over_current() {
  raise_error(error_bit::kTotalCurrent);
  ++over_current_count_;
  stop_all(false);
}

void Emulator::inject_position_difference(int function) {
  if (function < 1 || function > kMotionFunctionCount)
    throw std::out_of_range("scu emulator: no function F" + std::to_string(function));
  raise_error(error_bit::kPositionDifference);
  stop_function(index(function), false);
}

}  // namespace cellctl::scu

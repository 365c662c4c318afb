// scu::Emulator: what it is made of (its config, six actuators, the remote data's defaults), what one
// poll does and in which order, and what a test reads of its actuators. What it answers and how it
// moves are in the files beside this one (see emulator.hpp).
#include "scu/emulator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cellctl::scu {

Emulator::Emulator(link::Link& link, const EmulatorConfig& config) : link_(link), config_(config) {
  validate(config_);
  actuators_.reserve(kActuatorCount);
  for (const auto& a : config_.actuators) actuators_.emplace_back(a.physics);
  for (auto& obj : cyclic_objects_) obj.fill(kUnusedDataId);
  remote_speed_.fill(config_.default_speed_percent);
  owner_.fill(-1);
  initialised_ = config_.initialised;
  // Remote position default: Memory 1 of user 1.
  for (std::size_t a = 0; a < remote_position_.size(); ++a) {
    const auto& act = config_.actuators[a];
    remote_position_[a] = static_cast<std::int32_t>(
        std::lround(kUserPositionFractions[0] * act.physics.stroke_mm * act.edges_per_mm));
  }
}

std::size_t Emulator::present_index(int a) const {
  if (!present(a)) throw std::out_of_range("scu emulator: no actuator " + std::to_string(a));
  return index(a);
}

plant::Actuator& Emulator::actuator(int a) {
  return actuators_[present_index(a)];
}

const plant::Actuator& Emulator::actuator(int a) const {
  return actuators_[present_index(a)];
}

std::int32_t Emulator::position_edges(int a) const {
  if (!present(a)) return 0;
  return static_cast<std::int32_t>(
      std::lround(actuators_[index(a)].position_mm() * config_.actuators[index(a)].edges_per_mm));
}

Status1 Emulator::status1(int a) const {
  if (!present(a)) return {};
  const auto& p = actuators_[index(a)];
  Status1 s;
  s.present = true;
  s.limit_signal = p.at_in_limit() || p.at_out_limit();
  // Motion active follows the plant: a commanded motion that is not stalled (below the minimum speed
  // or jammed, the motor does not turn and the SCU does not report motion).
  s.motion_active = p.active() && !p.stalled();
  s.in_position = p.at_in_limit();
  s.out_position = p.at_out_limit();
  s.stroke_recorded = true;
  return s;
}

void Emulator::poll(link::TimePoint now) {
  if (last_poll_ && now > *last_poll_) step_plant(now - *last_poll_);
  if (!last_poll_ || now > *last_poll_) last_poll_ = now;
  // What has arrived is read before the watchdog is judged: when this thread was kept off the CPU,
  // an RC that came in time must not count as missing.
  receive(now);
  run_watchdog(now);
  flush(now);
}

}  // namespace cellctl::scu

#pragma once
// What an emulated SCU is: its actuators (physics and encoder edges per mm), its function
// parameterization, and the defaults of its remote data. Plain data, filled from the cell config's
// scu.emulator part (controller/config/scu_section) or directly by tests.

#include <array>
#include <cstdint>
#include <string>

#include "plant/actuator.hpp"
#include "scu/functions.hpp"

namespace cellctl::scu {

struct EmulatedActuator {
  bool present = false;
  plant::ActuatorParams physics;
  double edges_per_mm = 100.0;  // SCU positions are encoder edges
};

struct EmulatorConfig {
  std::array<EmulatedActuator, kActuatorCount> actuators{};  // actuators[a-1] is An
  FunctionTable functions{};
  std::uint16_t default_speed_percent = 100;  // remote speed 0x3011.. after reset
  // Status 2 bit 0 at power-up, per actuator [a-1]: not initialised unless set (tests).
  std::array<bool, kActuatorCount> initialised{};
  // The manual does not say whether an RE is taken while an actuator still ramps down from the RS
  // before it; this emulator takes it (and the actuator on from its speed) unless this is set, when
  // it answers PE, as a stricter SCU might (tests of how the controller reports that).
  bool refuses_execute_while_moving = false;
  std::string firmware = "SCU V2B3 cellctl emulator";
  std::string configuration = "SCP11 cellctl emulator";
};

// Throws std::invalid_argument naming the field and the value (a function moving an absent actuator,
// edges_per_mm ≤ 0, a speed above 100 %).
void validate(const EmulatorConfig& c);

// n actuators with the same physics, SCP11 functions: the usual test and demo set-up.
[[nodiscard]] EmulatorConfig scp11_emulator(int actuators, const plant::ActuatorParams& physics,
                                            double edges_per_mm);

}  // namespace cellctl::scu

#pragma once
// The emulated plant's state between dry runs, as a powered cell keeps it between two jobs: where
// each SCU actuator's rod stands and whether the SCU has initialised it (status 2 bit 0), and the
// spindle converter's operating hours. The encoder needs nothing here: its shaft follows the
// actuator it is coupled to, and its EEPROM has its own file (encoder::save_eeprom). A power loss
// is deliberate (power_cycled): the rods stay where they are, the initialised bits are lost.

#include <array>
#include <filesystem>
#include <optional>

#include "emulation/emulator_setup.hpp"
#include "scu/functions.hpp"

namespace cellctl::runtime {

class EmulatedCell;

struct PlantState {
  struct Actuator {
    double position_mm = 0.0;  // the SCU's own (indicated) position, what start_position_mm means
    bool initialised = false;
  };
  std::array<std::optional<Actuator>, scu::kActuatorCount> actuators{};  // [a-1]; empty: not kept
  std::optional<double> spindle_converter_hours;
  std::optional<double> spindle_motor_hours;
};

// Missing file: nothing kept (an emulator as after power-up). A file that is not this JSON:
// std::runtime_error naming the file and what is wrong.
[[nodiscard]] PlantState load_plant_state(const std::filesystem::path& path);
// A temporary file, flushed, renamed over `path` (folders made); false when that fails.
[[nodiscard]] bool save_plant_state(const std::filesystem::path& path, const PlantState& state) noexcept;

// What the emulators of `cell` hold now.
[[nodiscard]] PlantState plant_state_of(EmulatedCell& cell);
// The state after a power loss and return: positions kept, nothing initialised.
[[nodiscard]] PlantState power_cycled(PlantState state);
// `setup` with the emulators starting from `state` (actuators the SCU set-up does not have are left out).
void start_from(emulation::EmulatorSetup& setup, const PlantState& state);

}  // namespace cellctl::runtime

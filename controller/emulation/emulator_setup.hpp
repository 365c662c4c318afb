#pragma once
// The emulated devices' set-up, read from the cell config only where emulators are built (the
// controller core and the sessions never see it), from the file as config/ parsed it: each emulator mirrors
// its device's session settings (actuators and functions, station address, functionality, line) and adds its
// physics — actuator ramps and scale error, the converter's motor and identification, the encoder's
// resolution and EEPROM file — and the plant that couples them (the encoder's shaft slip).

#include <filesystem>
#include <optional>

#include "config/cell_config.hpp"
#include "config/yaml_node.hpp"
#include "encoder/emulator.hpp"
#include "scu/emulator_config.hpp"
#include "spindle/emulator.hpp"

namespace cellctl::emulation {

// The emulated cell's physics beyond each device's own (what couples them): the encoder's shaft
// turns once per encoder_mm_per_revolution of the axis's true travel (its lead: mechanics, which no
// Teach-In changes; 0 takes the one the encoder section's scaling implies, a coupling that reads the
// axis exactly — with a taught config that is the taught belief, not the shaft), slips this fraction
// against the axis it measures, and is mounted so that it reads as if the axis stood encoder_mount_mm
// further (a replaced or remounted encoder reads the same axis differently).
struct PlantConfig {
  double encoder_mm_per_revolution = 0.0;
  double encoder_slip = 0.0;
  double encoder_mount_mm = 0.0;
};

struct EmulatorSetup {
  std::optional<scu::EmulatorConfig> scu;  // present when the cell has the device
  std::optional<spindle::EmulatorConfig> spindle;
  std::optional<encoder::EmulatorConfig> encoder;
  PlantConfig plant;
  // Where the emulated plant keeps its state between runs (runtime/plant_state.hpp): read when the
  // emulators are built, written when they are destroyed. Empty: they start as after power-up and
  // keep nothing (the library's default, so tests stay independent of each other).
  std::filesystem::path plant_state_file;
  // The kept state is read as after a power loss: rods where they were, nothing initialised.
  bool power_cycle = false;
};

// Each throws config::ConfigError (file:line:column: field: rule) on an unknown key or a value out of
// range. The device parts take the device's section node and mirror its session's settings.
[[nodiscard]] scu::EmulatorConfig parse_scu_emulator(const config::YamlNode& scu_section,
                                                     const config::ScuSection& scu);
[[nodiscard]] spindle::EmulatorConfig parse_spindle_emulator(const config::YamlNode& spindle_section);
[[nodiscard]] encoder::EmulatorConfig parse_encoder_emulator(const config::YamlNode& encoder_section,
                                                             const encoder::SessionConfig& session);
[[nodiscard]] EmulatorSetup parse_emulator_setup(const config::YamlNode& root,
                                                 const config::CellConfig& cell);
// From the cell's file as config/ parsed it (cell.document; the file is not read again). Throws
// std::invalid_argument for a cell made in memory, which has no file.
[[nodiscard]] EmulatorSetup load_emulator_setup(const config::CellConfig& cell);

}  // namespace cellctl::emulation

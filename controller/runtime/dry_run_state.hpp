#pragma once
// What a dry run (--virtual-time, --emulate, `cellctl emulate`) may write: only its own state beside
// the cell's, in the state folder — never the cell's config or records. Beside the home records
// (home.virtual-time.json, home.emulated.json, runtime/home_record_file.hpp) it keeps:
//   <state_dir>/plant.dry-run.json     the emulated plant between dry runs (runtime/plant_state.hpp):
//                                      one emulated cell, shared by every dry run of this state folder;
//   <state_dir>/encoder.dry-run.eeprom the emulated encoder's EEPROM, when the config names no
//                                      encoder.emulator.state_file of its own;
//   <state_dir>/config.dry-run.yaml    the cell's config with a dry run's change in it (a Teach-In
//                                      rehearsal's result, an encoder preset on an emulator), to read
//                                      and apply deliberately.

#include <filesystem>

#include "config/cell_config.hpp"
#include "emulation/emulator_setup.hpp"

namespace cellctl::runtime {

[[nodiscard]] std::filesystem::path dry_run_plant_file(const std::filesystem::path& state_dir);
[[nodiscard]] std::filesystem::path dry_run_config_file(const std::filesystem::path& state_dir);

// The emulators of `cell` (load_emulator_setup) keeping their state in `state_dir` between dry runs;
// `power_cycle`: they start as after a power loss (rods where they were, no actuator initialised).
// Throws as load_emulator_setup.
[[nodiscard]] emulation::EmulatorSetup dry_run_emulator_setup(const config::CellConfig& cell,
                                                              const std::filesystem::path& state_dir,
                                                              bool power_cycle = false);

}  // namespace cellctl::runtime

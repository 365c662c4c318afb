#include "runtime/dry_run_state.hpp"

namespace cellctl::runtime {

std::filesystem::path dry_run_plant_file(const std::filesystem::path& state_dir) {
  return state_dir / "plant.dry-run.json";
}

std::filesystem::path dry_run_config_file(const std::filesystem::path& state_dir) {
  return state_dir / "config.dry-run.yaml";
}

emulation::EmulatorSetup dry_run_emulator_setup(const config::CellConfig& cell,
                                                const std::filesystem::path& state_dir, bool power_cycle) {
  auto setup = emulation::load_emulator_setup(cell);
  std::error_code ignored;  // a folder that cannot be made: the saves fail, the dry run goes on
  std::filesystem::create_directories(state_dir, ignored);
  setup.plant_state_file = dry_run_plant_file(state_dir);
  setup.power_cycle = power_cycle;
  // A state_file the config names is the emulator's own choice (kept); otherwise the EEPROM lives
  // with the rest of the dry-run plant.
  if (setup.encoder && setup.encoder->state_file.empty())
    setup.encoder->state_file = state_dir / "encoder.dry-run.eeprom";
  return setup;
}

}  // namespace cellctl::runtime

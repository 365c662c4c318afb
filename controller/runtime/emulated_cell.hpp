#pragma once
// The cell's devices as emulators, built from the cell config over whatever links they are given
// (pseudo-terminals for `cellctl emulate` and `run --emulate`, SimLinks in virtual time), sharing one
// plant: the encoder's shaft turns with the true position of the SCU actuator of the measured axis,
// so a dry run is physically consistent (a scale error in the actuator shows up at the encoder).

#include <memory>
#include <optional>

#include "config/cell_config.hpp"
#include "encoder/emulator.hpp"
#include "link/clock.hpp"
#include "link/link.hpp"
#include "plant/shaft.hpp"
#include "runtime/device_links.hpp"
#include "runtime/emulator_setup.hpp"
#include "scu/emulator.hpp"
#include "spindle/emulator.hpp"

namespace cellctl::runtime {

class EmulatedCell {
 public:
  // Throws std::invalid_argument / std::runtime_error from an emulator's set-up (config time).
  // With setup.plant_state_file, the emulators start from the state kept there (runtime/plant_state).
  EmulatedCell(const config::CellConfig& cell, const EmulatorSetup& setup, DeviceLinks links);
  // Keeps the plant's state in setup.plant_state_file, if any, for the next dry run.
  ~EmulatedCell();
  EmulatedCell(const EmulatedCell&) = delete;
  EmulatedCell& operator=(const EmulatedCell&) = delete;

  // Steps every emulator (and so the plant) to `now` and answers what has arrived.
  void poll(link::TimePoint now);

  // Fault hooks and inspection, nullptr where the device is not emulated.
  [[nodiscard]] scu::Emulator* scu() noexcept { return scu_.get(); }
  [[nodiscard]] spindle::Emulator* spindle() noexcept { return spindle_.get(); }
  [[nodiscard]] encoder::Emulator* encoder() noexcept { return encoder_.get(); }
  [[nodiscard]] plant::Shaft* shaft() noexcept { return shaft_ ? &*shaft_ : nullptr; }

 private:
  std::unique_ptr<scu::Emulator> scu_;
  std::unique_ptr<spindle::Emulator> spindle_;
  std::optional<plant::Shaft> shaft_;
  std::unique_ptr<encoder::Emulator> encoder_;
  std::filesystem::path plant_state_file_;
};

}  // namespace cellctl::runtime

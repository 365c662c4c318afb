#pragma once
// The cell's devices as emulators, made from the registry (device_seam/device_registry.hpp) for every
// device whose line it is given (pseudo-terminals for `cellctl emulate`, socket pairs for `run
// --emulate`, SimLinks in virtual time), in slot order, sharing one plant: the encoder's shaft turns
// with the true position of the SCU actuator of the measured axis, so a dry run is physically
// consistent (a scale error in the actuator shows up at the encoder).

#include <array>
#include <filesystem>
#include <memory>
#include <span>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/device_emulators.hpp"
#include "emulation/emulated_device.hpp"
#include "emulation/emulator_setup.hpp"
#include "link/clock.hpp"
#include "runtime/device_links.hpp"

namespace cellctl::runtime {

class EmulatedCell {
 public:
  // Throws std::invalid_argument / std::runtime_error from an emulator's set-up (config time).
  // With setup.plant_state_file, the emulators start from the state kept there (runtime/plant_state).
  EmulatedCell(const config::CellConfig& cell, const emulation::EmulatorSetup& setup,
               const DeviceLinks& links,
               std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());
  // Keeps the plant's state in setup.plant_state_file, if any, for the next dry run.
  ~EmulatedCell();
  EmulatedCell(const EmulatedCell&) = delete;
  EmulatedCell& operator=(const EmulatedCell&) = delete;

  // Steps every emulator (and so the plant) to `now` and answers what has arrived.
  void poll(link::TimePoint now);
  // The emulator in `slot` (nullptr: that device is not emulated).
  [[nodiscard]] emulation::EmulatedDevice* device(std::size_t slot) noexcept {
    return slot < made_.size() ? made_[slot] : nullptr;
  }
  // The emulator of type E (a device's own: scu::Emulator, …), nullptr when none is emulated.
  template <class E>
  [[nodiscard]] E* find() noexcept {
    return emulation::find_emulator<E>(made_);
  }

  // Fault hooks and inspection of the cell's three, nullptr where the device is not emulated.
  [[nodiscard]] scu::Emulator* scu() noexcept { return find<scu::Emulator>(); }
  [[nodiscard]] spindle::Emulator* spindle() noexcept { return find<spindle::Emulator>(); }
  [[nodiscard]] encoder::Emulator* encoder() noexcept { return find<encoder::Emulator>(); }
  [[nodiscard]] plant::Shaft* shaft() noexcept;

 private:
  std::array<std::unique_ptr<emulation::EmulatedDevice>, cell::kMaxDevices> owned_;
  std::array<emulation::EmulatedDevice*, cell::kMaxDevices> made_{};  // by slot, as they are made
  std::filesystem::path plant_state_file_;
};

}  // namespace cellctl::runtime

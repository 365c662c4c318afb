#pragma once
// One device's emulator as the emulated cell (runtime::EmulatedCell) steps it, whatever the device:
// the device side of the seam that device_seam::CellDevice is on the controller's side. Each kind of
// device registers how its emulator is made (device_seam/device_registry.hpp); the emulated cell
// polls them in slot order and a fault rehearsal turns their own error on and off through it.

#include <span>

#include "config/cell_config.hpp"
#include "emulation/emulator_setup.hpp"
#include "link/clock.hpp"
#include "link/link.hpp"

namespace cellctl::emulation {

class EmulatedDevice {
 public:
  virtual ~EmulatedDevice() = default;
  EmulatedDevice() = default;
  EmulatedDevice(const EmulatedDevice&) = delete;
  EmulatedDevice& operator=(const EmulatedDevice&) = delete;

  // Steps the emulator (and its physics) to `now` and answers what has arrived on its line.
  virtual void poll(link::TimePoint now) = 0;
  // The device's own error as its manual describes it (a fault rehearsal's `error`), on or off.
  virtual void set_own_error(bool on) = 0;
};

// An emulator of type E seen as an EmulatedDevice, so that what knows E (the plant's kept state, a
// test's fault hooks, another emulator coupled to it) finds it among the cell's.
template <class E>
class EmulatorOf : public EmulatedDevice {
 public:
  [[nodiscard]] virtual E& emulator() noexcept = 0;
};

// The first emulator of type E among `devices` (nullptr entries skipped), or nullptr.
template <class E>
[[nodiscard]] E* find_emulator(std::span<EmulatedDevice* const> devices) noexcept {
  for (auto* d : devices)
    if (auto* of = dynamic_cast<EmulatorOf<E>*>(d)) return &of->emulator();
  return nullptr;
}

// What an emulator is made from: the cell, the emulated cell's set-up, the device's end of its line,
// and the emulators made before it (slot order: the encoder's shaft turns with an SCU actuator).
struct EmulatorContext {
  const config::CellConfig& cell;
  const EmulatorSetup& setup;
  link::Link& link;
  std::span<EmulatedDevice* const> made;
};

}  // namespace cellctl::emulation

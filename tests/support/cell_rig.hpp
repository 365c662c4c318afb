#pragma once
// The cell's devices as CellRun assembles them in virtual time — a simulated line per kind of device
// whose port the config names, the emulators on their far ends, the devices above their sessions — and
// stepped one control cycle at a time without the supervisor, for tests of what lies between the lines
// and the cell state (the device seam, a device's adapter).

#include <chrono>
#include <span>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulator_setup.hpp"
#include "link/clock.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/emulated_cell.hpp"

namespace cellctl::testing {

struct CellRig {
  explicit CellRig(config::CellConfig cell_config,
                   std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds())
      : cell(std::move(cell_config)),
        setup(emulation::load_emulator_setup(cell)),
        links(cell, runtime::RunMode::virtual_time, clock, false, {}, kinds),
        emulated(cell, setup, links.device(), kinds),
        devices(
            cell, links.master(), [this](std::size_t slot) { return links.reopen(slot).ok(); }, kinds) {}

  // The emulators answer, the devices read the cell state; then the intents go out (as CellRun's cycle).
  void receive() {
    const auto now = clock.now();
    emulated.poll(now);
    devices.receive(now);
    devices.read(now, state);
  }
  void transmit(const cell::Intents& intents) {
    devices.apply(intents);
    devices.transmit(clock.now());
    clock.advance(std::chrono::milliseconds(1));
  }

  link::VirtualClock clock;
  config::CellConfig cell;
  emulation::EmulatorSetup setup;
  runtime::CellLinks links;
  runtime::EmulatedCell emulated;
  runtime::CellDevices devices;
  cell::CellState state;
};

}  // namespace cellctl::testing

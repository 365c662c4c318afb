#pragma once
// What a run on the cell (CellRun: a recipe, a homing, a Teach-In) opens before its loop starts: the
// cycle waiter for the mode, the faults to rehearse, the links, the emulators where
// devices are emulated, and the device sessions; and the emulators' own thread in real time.

#include <atomic>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulator_setup.hpp"
#include "link/clock.hpp"
#include "loop/cycle_waiter.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/emulated_cell.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::runtime {

struct CellParts {
  std::unique_ptr<loop::CycleWaiter> waiter;
  std::unique_ptr<FaultRehearsal> rehearsal;  // none without faults
  std::unique_ptr<CellLinks> links;
  std::unique_ptr<EmulatedCell> emulated;  // none when no device is emulated
  std::unique_ptr<CellDevices> devices;
};

// `clock` is `virtual_clock` in virtual time. `emulators` is read from the cell's file when needed and
// not given. `kinds`: the kinds of device the cell may have (the registry's, unless a test adds one). Throws
// std::invalid_argument (faults on hardware, a device the cell lacks), link::LinkError (a port),
// config::ConfigError / std::runtime_error (an emulator's set-up).
[[nodiscard]] CellParts open_cell_parts(const config::CellConfig& cell, RunMode mode,
                                        const link::Clock& clock, link::VirtualClock& virtual_clock,
                                        bool trace, const std::vector<FaultSpec>& faults,
                                        std::optional<emulation::EmulatorSetup>& emulators,
                                        std::span<const device_seam::DeviceKind> kinds);

// The hash of the cell's config file, which the home record is checked against ("" for a cell made in
// memory: no file).
[[nodiscard]] std::string config_sha256(const config::CellConfig& cell);

// The emulators' thread in real time: they answer like hardware, on their own time, until `stop`.
void serve_emulators(const std::atomic<bool>& stop, const link::Clock& clock, FaultRehearsal* rehearsal,
                     EmulatedCell& emulated);

}  // namespace cellctl::runtime

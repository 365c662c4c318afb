#pragma once
// A look at the cell while no job runs (`cellctl serve` before its first job): the links opened and
// the devices' sessions activated as a run opens them, the cell read until every device has answered
// (the SCU its positions and initialised bits, the encoder in data exchange) or a bound has passed,
// then every device brought to rest and closed as at a run's end (SafeStop), and the links closed.
// Nothing is commanded: no intents reach the devices — no move, no spindle start, no preset — only
// what a run's start-up and end send anyway (the SCU's remote mode opened, its keep-alive and status
// polls, then its motions stopped and remote mode closed; the converter's status polls and its stop).
// In a dry run the emulated plant is the one the jobs share: it is read as they left it.
//
// What it read is what a job's run shows of the cell (cell_view.hpp) and what its journal samples
// (supervisor/cell_sample.hpp): the page's axes and devices and the plant's Idle status show it from
// the start, through the same paths a job's end leaves them on.

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulator_setup.hpp"
#include "journal/event.hpp"
#include "runtime/cell_links.hpp"
#include "status/status_view.hpp"

namespace cellctl::runtime {

struct LookOptions {
  RunMode mode = RunMode::emulated;
  std::filesystem::path state_dir;  // the home record's folder; empty: the cell config's
  bool trace = false;
  // The emulated devices' set-up (a dry run's, to read the plant the jobs share); read from the
  // cell's file when emulators are needed and none is given.
  std::optional<emulation::EmulatorSetup> emulators;
  // How long, on the mode's clock, the devices have to answer before the cell is taken as read.
  double answer_within_s = 5.0;
  // How long a stop is sent again to a device that has not confirmed it (as a run's,
  // RunOptions::shutdown_timeout_s).
  double shutdown_timeout_s = 5.0;
  std::span<const device_seam::DeviceKind> device_kinds = device_seam::cell_device_kinds();
};

struct CellLook {
  status::StatusView view;  // Idle, no step: the cell as read (link figures of the look itself)
  journal::Sample sample;   // each axis planned where it stands, no spindle speed asked for
  bool answered = false;    // every device answered within the bound
  std::string words;        // what was read, which device did not answer, a safe state unknown
};

// Throws what a run's set-up throws before it moves (runtime/cell_parts.hpp: a port that does not
// open, an emulator's set-up).
[[nodiscard]] CellLook look_at_cell(const config::CellConfig& cell, LookOptions options);

}  // namespace cellctl::runtime

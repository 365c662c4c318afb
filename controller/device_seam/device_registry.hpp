#pragma once
// The kinds of device a cell may have: the one place a device is registered, with both its sides.
// runtime::CellLinks opens a line for every kind whose port the cell's config names,
// runtime::EmulatedCell makes each emulated one's emulator, runtime::CellDevices makes the devices
// above their sessions, and a fault rehearsal names a device and its own error from here — each in
// slot order (a device's slot is its place here: cell::Device for the three of the cell). Everything
// that iterates the cell's devices — the cycle, the safe-stop, the run record's verdicts and notes,
// the status and /metrics — iterates what was made from it. A test adds a kind of its own (a fake
// digital I/O module) through a DeviceKinds span alone.

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "config/cell_config.hpp"
#include "config/line_section.hpp"
#include "device_seam/cell_device.hpp"
#include "emulation/emulated_device.hpp"
#include "link/link.hpp"

namespace cellctl::device_seam {

struct DeviceKind {
  std::string_view name;  // as the config's section, the journal, the metrics and --fault name it
  // What its own error (a rehearsed `DEVICE:error`) does, in words, as its manual describes it.
  std::string_view own_error;
  // Its port when the cell's config has its section (else nullopt: the cell has no such device).
  std::optional<config::PortConfig> (*port)(const config::CellConfig& cell) = nullptr;
  // The device above its session on `link`. Throws std::invalid_argument (the session's config).
  std::unique_ptr<CellDevice> (*make)(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                                      CellDevice::Reopen reopen) = nullptr;
  // Its emulator on the device's end of the line, or nullptr when the set-up has none for it. Throws
  // std::invalid_argument / std::runtime_error (the emulator's set-up).
  std::unique_ptr<emulation::EmulatedDevice> (*make_emulator)(const emulation::EmulatorContext& context) =
      nullptr;
};

// The kinds of device of the cell in slot order: the SCU, the spindle converter, the encoder
// (cell::Device's order).
[[nodiscard]] std::span<const DeviceKind> cell_device_kinds() noexcept;

// The kind named `name` among `kinds`, or nullptr.
[[nodiscard]] const DeviceKind* find_kind(std::span<const DeviceKind> kinds, std::string_view name) noexcept;

// The cell config at `path` (config::load_cell_config), whose device sections are those of `kinds`, each
// read by its kind (its port): a problem in any of them is a ConfigError (file:line:column) here,
// before anything is opened.
[[nodiscard]] config::CellConfig load_cell_config(const std::filesystem::path& path,
                                                  std::span<const DeviceKind> kinds = cell_device_kinds());
[[nodiscard]] config::CellConfig parse_cell_config(const config::YamlNode& root,
                                                   const std::filesystem::path& source,
                                                   std::span<const DeviceKind> kinds = cell_device_kinds());

}  // namespace cellctl::device_seam

#pragma once
// The kinds of device a cell may have, and how each is made above its session: the one place a device
// is registered. runtime::CellDevices makes the cell's devices from it in slot order (a device's slot
// is its place here: cell::Device for the three of the cell), and everything that iterates the cell's
// devices — the cycle, the safe-stop, the run record's verdicts and notes — iterates what it made.
// A test adds a kind of its own (a fake digital I/O module) through DeviceKinds alone.

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "config/cell_config.hpp"
#include "device_seam/cell_device.hpp"
#include "link/link.hpp"

namespace cellctl::device_seam {

struct DeviceKind {
  std::string_view name;  // as the config, the journal and the metrics name it
  // The device above its session on `link`, or nullptr when the cell's config has no section for it.
  // Throws std::invalid_argument (the session's config).
  std::unique_ptr<CellDevice> (*make)(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                                      CellDevice::Reopen reopen) = nullptr;
};

// The kinds of device of the cell in slot order: the SCU, the spindle converter, the encoder
// (cell::Device's order).
[[nodiscard]] std::span<const DeviceKind> cell_device_kinds() noexcept;

}  // namespace cellctl::device_seam

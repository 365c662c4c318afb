#pragma once
// What the controller core (recipe checks, monitor, planner, supervisor) reads of the cell: its name,
// its axes, the limits it is held to, its stop reactions and the loop's timing. No device section and
// no emulator set-up: those are read where sessions (config/cell_config.hpp) and emulators
// (runtime/emulator_setup.hpp) are built.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "config/axis_section.hpp"
#include "config/cell_limits.hpp"
#include "config/yaml_node.hpp"

namespace cellctl::config {

struct CellCore {
  std::string name;
  std::filesystem::path source;  // the file it came from, for messages
  std::vector<AxisConfig> axes;
  CellLimits limits;
  StopReactions stops;
  LoopConfig loop;
  // How long a command may wait anywhere (a web worker's queue, the link's, the arbiter) and still
  // be obeyed; older ones are answered "expired" (command/order.hpp).
  int max_command_age_ms = 2000;

  // The axis with this name, or nullptr.
  [[nodiscard]] const AxisConfig* axis(std::string_view axis_name) const noexcept;
};

// The core keys of a cell config (cell, axes, limits, stops, loop, max_command_age_ms); the caller checks
// unknown keys, since the file holds the device sections too. Throws ConfigError (file:line:column: field:
// rule).
[[nodiscard]] CellCore parse_cell_core(const YamlNode& root, const std::filesystem::path& source);

}  // namespace cellctl::config

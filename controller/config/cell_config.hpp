#pragma once
// The cell: which devices, on which ports, with which session settings and — for the emulated
// ones — which emulator set-up. Loaded and validated completely before anything is opened.

#include <filesystem>
#include <string>

#include "config/axis_section.hpp"
#include "config/cell_limits.hpp"
#include "config/encoder_section.hpp"
#include "config/scu_section.hpp"
#include "config/spindle_section.hpp"
#include "config/yaml_node.hpp"

namespace cellctl::config {

struct CellConfig {
  std::string name;
  std::filesystem::path source;  // the file it came from, for messages
  std::vector<AxisConfig> axes;
  CellLimits limits;
  StopReactions stops;
  LoopConfig loop;
  std::optional<SpindleSection> spindle;
  std::optional<EncoderSection> encoder;
  std::optional<ScuSection> scu;
  PlantConfig plant;

  // The axis with this name, or nullptr.
  [[nodiscard]] const AxisConfig* axis(std::string_view axis_name) const noexcept;
};

// Throws ConfigError (file:line:column: field: rule) on the first problem.
[[nodiscard]] CellConfig load_cell_config(const std::filesystem::path& path);
[[nodiscard]] CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source);

}  // namespace cellctl::config

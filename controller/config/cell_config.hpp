#pragma once
// The cell as the program that drives it sees it: the core (axes, limits, stops, loop) and, per
// device, its port and session settings. Loaded and validated completely before anything is opened.
// The emulators' set-up is not here: runtime/emulator_setup reads it where emulators are built.

#include <filesystem>
#include <optional>

#include "config/cell_core.hpp"
#include "config/encoder_section.hpp"
#include "config/scu_section.hpp"
#include "config/spindle_section.hpp"
#include "config/yaml_node.hpp"

namespace cellctl::config {

struct CellConfig : CellCore {
  std::optional<SpindleSection> spindle;
  std::optional<EncoderSection> encoder;
  std::optional<ScuSection> scu;
  // Where the cell keeps what outlives a process (the home record): `state` beside runs/ in the
  // working directory unless the config names a folder (then relative to the config file, as every
  // path in a config: YamlNode::as_path).
  std::filesystem::path state_dir = "state";
};

// Throws ConfigError (file:line:column: field: rule) on the first problem.
[[nodiscard]] CellConfig load_cell_config(const std::filesystem::path& path);
[[nodiscard]] CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source);

}  // namespace cellctl::config

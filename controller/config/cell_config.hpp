#pragma once
// The cell as the program that drives it sees it: the core (axes, limits, stops, loop) and, per
// device, its port and session settings. Loaded and validated completely before anything is opened.
// The emulators' set-up and the plant link are not here: they are read where they are built
// (runtime/emulator_setup, plant_link/link_config), from the file as parsed here (`document`), so the
// file is parsed once and their errors still name file:line:column.

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
  // The whole file as parsed, for the sections read where their parts are built (their nodes carry
  // file:line:column); none for a cell made in memory.
  std::optional<YamlNode> document;
};

// Throws ConfigError (file:line:column: field: rule) on the first problem.
[[nodiscard]] CellConfig load_cell_config(const std::filesystem::path& path);
[[nodiscard]] CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source);

}  // namespace cellctl::config

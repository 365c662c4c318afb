#pragma once
// The cell as the program that drives it sees it: the core (axes, limits, stops, loop) and, per
// device, its port and session settings. Loaded and validated completely before anything is opened.
// The emulators' set-up and the plant link are not here: they are read where they are built
// (runtime/emulator_setup, plant_link/link_config), from the file as parsed here (`document`), so the
// file is parsed once and their errors still name file:line:column.

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>

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

// The sections a cell's devices may have: the three of the cell. A device registered beyond them
// (device_seam/device_registry.hpp) has its section read where it is made, from `document`.
inline constexpr std::array<std::string_view, 3> kCellDeviceSections = {"scu", "spindle", "encoder"};

// Throws ConfigError (file:line:column: field: rule) on the first problem. `device_sections`: the
// top-level keys that name a device (device_seam::load_cell_config passes the registry's).
[[nodiscard]] CellConfig load_cell_config(
    const std::filesystem::path& path,
    std::span<const std::string_view> device_sections = kCellDeviceSections);
[[nodiscard]] CellConfig parse_cell_config(
    const YamlNode& root, const std::filesystem::path& source,
    std::span<const std::string_view> device_sections = kCellDeviceSections);

}  // namespace cellctl::config

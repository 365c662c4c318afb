#pragma once
// The cell: which devices, on which ports, with which session settings and — for the emulated
// ones — which emulator set-up. Loaded and validated completely before anything is opened.

#include <filesystem>
#include <string>

#include "config/yaml_node.hpp"

namespace cellctl::config {

struct CellConfig {
  std::string name;
  std::filesystem::path source;  // the file it came from, for messages
};

// Throws ConfigError (file:line:column: field: rule) on the first problem.
[[nodiscard]] CellConfig load_cell_config(const std::filesystem::path& path);
[[nodiscard]] CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source);

}  // namespace cellctl::config

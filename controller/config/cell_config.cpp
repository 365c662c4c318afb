#include "config/cell_config.hpp"

namespace cellctl::config {

CellConfig load_cell_config(const std::filesystem::path& path) {
  return parse_cell_config(YamlNode::load_file(path), path);
}

CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source) {
  root.only_keys({"cell", "scu", "spindle", "encoder"});
  CellConfig cell;
  cell.source = source;
  cell.name = root.string_at("cell");
  return cell;
}

}  // namespace cellctl::config

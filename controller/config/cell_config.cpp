#include "config/cell_config.hpp"

#include "config/cell_checks.hpp"

namespace cellctl::config {

CellConfig load_cell_config(const std::filesystem::path& path,
                            std::span<const std::string_view> device_sections) {
  return parse_cell_config(YamlNode::load_file(path), path, device_sections);
}

CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source,
                             std::span<const std::string_view> device_sections) {
  // `plant` is the emulated cell's coupling: read with the emulators' set-up, allowed here;
  // `plant_link` (the MQTT link to the plant) is read by controller/plant_link where the link is built.
  // Both read them from `document`, this parse of the file.
  root.only_keys(
      {"cell", "axes", "limits", "stops", "loop", "plant", "plant_link", "state_dir", "max_command_age_ms"},
      device_sections);
  CellConfig cell;
  static_cast<CellCore&>(cell) = parse_cell_core(root, source);
  cell.state_dir = root.path_or("state_dir", cell.state_dir);  // relative to the config file
  if (auto n = root.maybe("spindle")) cell.spindle = parse_spindle_section(*n);
  if (auto n = root.maybe("encoder")) cell.encoder = parse_encoder_section(*n);
  if (auto n = root.maybe("scu")) cell.scu = parse_scu_section(*n);
  check_cell(root, cell);
  cell.document = root;
  return cell;
}

}  // namespace cellctl::config

#include "config/cell_config.hpp"

#include "config/cell_checks.hpp"

namespace cellctl::config {

const AxisConfig* CellConfig::axis(std::string_view axis_name) const noexcept {
  for (const auto& a : axes)
    if (a.name == axis_name) return &a;
  return nullptr;
}

CellConfig load_cell_config(const std::filesystem::path& path) {
  return parse_cell_config(YamlNode::load_file(path), path);
}

CellConfig parse_cell_config(const YamlNode& root, const std::filesystem::path& source) {
  root.only_keys({"cell", "axes", "limits", "stops", "loop", "plant", "scu", "spindle", "encoder"});
  CellConfig cell;
  cell.source = source;
  cell.name = root.string_at("cell");
  cell.axes = parse_axes(root.at("axes"));
  if (auto n = root.maybe("limits")) cell.limits = parse_cell_limits(*n);
  if (auto n = root.maybe("stops")) cell.stops = parse_stop_reactions(*n);
  if (auto n = root.maybe("loop")) cell.loop = parse_loop(*n);
  if (auto n = root.maybe("spindle")) cell.spindle = parse_spindle_section(*n);
  if (auto n = root.maybe("encoder")) cell.encoder = parse_encoder_section(*n);
  if (auto n = root.maybe("scu")) cell.scu = parse_scu_section(*n);
  if (auto n = root.maybe("plant")) cell.plant = parse_plant(*n);
  check_cell(root, cell);
  return cell;
}

}  // namespace cellctl::config

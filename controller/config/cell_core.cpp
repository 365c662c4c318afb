#include "config/cell_core.hpp"

namespace cellctl::config {

const AxisConfig* CellCore::axis(std::string_view axis_name) const noexcept {
  for (const auto& a : axes)
    if (a.name == axis_name) return &a;
  return nullptr;
}

CellCore parse_cell_core(const YamlNode& root, const std::filesystem::path& source) {
  CellCore cell;
  cell.source = source;
  cell.name = root.string_at("cell");
  cell.axes = parse_axes(root.at("axes"));
  if (auto n = root.maybe("limits")) cell.limits = parse_cell_limits(*n);
  if (auto n = root.maybe("stops")) cell.stops = parse_stop_reactions(*n);
  if (auto n = root.maybe("loop")) cell.loop = parse_loop(*n);
  cell.max_command_age_ms = root.int_in_or<int>("max_command_age_ms", 100, 60000, cell.max_command_age_ms);
  return cell;
}

}  // namespace cellctl::config

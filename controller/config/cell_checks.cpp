#include "config/cell_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "config/cell_config.hpp"

namespace cellctl::config {

void check_cell(const YamlNode& root, CellConfig& cell) {
  const auto axes = root.at("axes").items();
  bool measured = false;
  for (std::size_t i = 0; i < cell.axes.size(); ++i) {
    auto& axis = cell.axes[i];
    const auto& node = axes[i];
    measured = measured || axis.encoder;
    if (!cell.scu) {
      if (axis.edges_per_mm <= 0.0) node.fail("edges_per_mm is needed when the cell has no scu section");
      axis.full_speed_mm_s = axis.max_speed_mm_s;
      continue;
    }
    const auto& scu = *cell.scu;
    const auto& act = scu.emulator.actuators[static_cast<std::size_t>(axis.actuator - 1)];
    if (!scu.session.actuators.test(static_cast<std::size_t>(axis.actuator - 1)))
      node.at("actuator").fail(fmt::format("the scu section has no actuator {}", axis.actuator));
    const auto& fn = scu.session.functions[static_cast<std::size_t>(axis.function - 1)];
    if (!fn.defined)
      node.at("function").fail(fmt::format("the scu section has no function {}", axis.function));
    if (fn.actuators.count() != 1 || !fn.moves(axis.actuator))
      node.at("function")
          .fail(fmt::format("function {} must move actuator {} alone to drive axis '{}'", axis.function,
                            axis.actuator, axis.name));
    if (axis.edges_per_mm <= 0.0) {
      axis.edges_per_mm = act.edges_per_mm;
    } else if (std::abs(axis.edges_per_mm - act.edges_per_mm) > 1e-9) {
      node.at("edges_per_mm")
          .fail(fmt::format(
              "{:g} disagrees with the SCU's actuator {} ({:g}); state it once, in the scu section",
              axis.edges_per_mm, axis.actuator, act.edges_per_mm));
    }
    if (axis.max_mm > act.physics.stroke_mm)
      node.at("max_mm").fail(fmt::format("{:g} mm is beyond actuator {}'s stroke of {:g} mm", axis.max_mm,
                                         axis.actuator, act.physics.stroke_mm));
    axis.full_speed_mm_s = act.physics.max_speed_mm_s;
    if (axis.max_speed_mm_s > axis.full_speed_mm_s)
      node.at("max_speed_mm_s")
          .fail(fmt::format("{:g} mm/s is beyond actuator {}'s full speed of {:g} mm/s", axis.max_speed_mm_s,
                            axis.actuator, axis.full_speed_mm_s));
    if (axis.min_mm < 0.0) node.at("min_mm").fail("an actuator's travel starts at 0 mm (fully in)");
  }
  if (cell.encoder && !measured)
    root.at("axes").fail("the cell has an encoder: mark the axis it measures with 'encoder: true'");
  if (!cell.encoder && measured)
    root.at("axes").fail("an axis is marked 'encoder: true' but the cell has no encoder section");
}

}  // namespace cellctl::config

#include "routines/home_record.hpp"

#include <cmath>

namespace cellctl::routines {

double expected_encoder_mm(const AxisHome& home, double scu_mm) noexcept {
  return scu_mm + (home.encoder_mm - home.scu_mm);
}

journal::Text check_homed(const HomeRecord& record, const config::CellCore& cell, const cell::CellState& s,
                          std::size_t axis) {
  const auto& c = cell.axes[axis];
  const auto& home = record.axes[axis];
  const auto& a = s.axes[axis];
  if (c.homing.strategy == config::HomingStrategy::none)
    return journal::Text::format("axis {} has no homing in the cell config (axes[].homing)", c.name);
  if (!home.homed)
    return journal::Text::format("axis {} has no home record: home it first (cellctl home {})", c.name,
                                 c.name);
  if (record.config_changed || home.strategy != c.homing.strategy)
    return journal::Text::format("axis {}: the cell config changed since it was homed: home it again",
                                 c.name);
  if (c.homing.strategy != config::HomingStrategy::absolute_encoder && !a.scu_initialised)
    return journal::Text::format(
        "axis {}: the SCU reports actuator {} not initialised (power loss or reset since homing): home "
        "it again",
        c.name, c.actuator);
  if (!home.measured) return {};
  if (!(s.encoder.data_exchange && s.encoder.ready))
    return journal::Text::format("axis {}: the encoder is not ready, its home cannot be checked", c.name);
  const double expected = expected_encoder_mm(home, a.scu_mm);
  if (std::abs(a.encoder_mm - expected) > c.homing.tolerance_mm)
    return journal::Text::format(
        "axis {}: encoder at {:.2f} mm, home record expects {:.2f} ± {:g} mm (SCU {:.2f} mm): encoder "
        "replaced or moved? home again",
        c.name, a.encoder_mm, expected, c.homing.tolerance_mm, a.scu_mm);
  return {};
}

}  // namespace cellctl::routines

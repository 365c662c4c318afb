#include "scu/emulator_config.hpp"

#include <stdexcept>
#include <string>

namespace cellctl::scu {

void validate(const EmulatorConfig& c) {
  for (std::size_t a = 0; a < c.actuators.size(); ++a) {
    const auto& act = c.actuators[a];
    if (act.present && !(act.edges_per_mm > 0.0))
      throw std::invalid_argument("scu emulator: actuators[" + std::to_string(a + 1) +
                                  "].edges_per_mm must be > 0, got " + std::to_string(act.edges_per_mm));
  }
  for (std::size_t f = 0; f < c.functions.size(); ++f) {
    const auto& fn = c.functions[f];
    if (!fn.defined) continue;
    if (fn.actuators.none())
      throw std::invalid_argument("scu emulator: function F" + std::to_string(f + 1) + " moves no actuator");
    for (int a = 1; a <= kActuatorCount; ++a)
      if (fn.moves(a) && !c.actuators[static_cast<std::size_t>(a - 1)].present)
        throw std::invalid_argument("scu emulator: function F" + std::to_string(f + 1) + " moves actuator " +
                                    std::to_string(a) + ", which is not configured");
  }
  if (c.default_speed_percent > 100)
    throw std::invalid_argument("scu emulator: default_speed_percent must be 0..100, got " +
                                std::to_string(c.default_speed_percent));
}

EmulatorConfig scp11_emulator(int actuators, const plant::ActuatorParams& physics, double edges_per_mm) {
  EmulatorConfig c;
  std::bitset<kActuatorCount> present;
  for (int a = 0; a < actuators && a < kActuatorCount; ++a) {
    c.actuators[static_cast<std::size_t>(a)] = {true, physics, edges_per_mm};
    present.set(static_cast<std::size_t>(a));
  }
  c.functions = scp11(present);
  return c;
}

}  // namespace cellctl::scu

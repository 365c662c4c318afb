#pragma once
// How one axis is homed (the axis's `homing:` in the cell config), read by the core's axis parser.
// LinuxCNC's HOME_SEQUENCE is `sequence`: axes with the same number home together, lower numbers
// first. Checked at load: the strategy fits the axis (an absolute encoder needs the encoder on it),
// the speeds are ones the actuator moves at, the home position is inside the travel.

#include <cstdint>

#include "config/yaml_node.hpp"

namespace cellctl::config {

enum class HomingStrategy : std::uint8_t {
  none,              // the axis is not homed (a recipe may not require it homed)
  absolute_encoder,  // no motion: the encoder is the reference; it must agree with the home record
  end_position,      // drive to an end, preset the encoder there, go to the home position
  scu_initialised,   // the SCU's own initialisation (status 2 bit 0) is the reference
};
[[nodiscard]] const char* to_string(HomingStrategy s) noexcept;

enum class HomingEnd : std::uint8_t { retracted, extended };

struct HomingConfig {
  HomingStrategy strategy = HomingStrategy::none;
  int sequence = 0;
  HomingEnd end = HomingEnd::retracted;  // end_position / scu_initialised: the end driven to
  double speed_mm_s = 0.0;               // to the end (0: the axis's min_speed × 2, at least 2 mm/s)
  double preset_mm = 0.0;                // end_position with the encoder: what it reads at the end
  double home_mm = 0.0;                  // where the axis is left (not for absolute_encoder)
  double tolerance_mm = 0.5;             // home record vs devices, and the preset read back
};

struct AxisConfig;
// `homing:` of one axis (n is the axis's node). Throws ConfigError.
[[nodiscard]] HomingConfig parse_homing(const YamlNode& n, const AxisConfig& axis);

}  // namespace cellctl::config

#pragma once
// The cell's axes: each is one SCU actuator moved by one SCU function, with its scaling from mm to
// the SCU's encoder edges and the mechanical limits no recipe may exceed. At most one axis is
// measured by the absolute encoder, which closes the loop on it.

#include <string>
#include <vector>

#include "config/homing_section.hpp"
#include "config/yaml_node.hpp"

namespace cellctl::config {

// An axis name is quoted in refusals, faults and notes: bounded so that those texts are never cut
// (journal::Text's capacity assumes it).
inline constexpr std::size_t kAxisNameMax = 16;

struct AxisConfig {
  std::string name;
  int actuator = 1;           // SCU actuator 1..6
  int function = 1;           // SCU function F1..F10 that moves it (remote position + remote speed)
  double edges_per_mm = 0.0;  // SCU edges per mm: from the scu section's actuator unless given here
  double min_mm = 0.0;        // the cell's travel limits for this axis (safety monitor and validator)
  double max_mm = 100.0;
  double max_speed_mm_s = 20.0;  // the fastest the cell lets this axis go
  double full_speed_mm_s = 0.0;  // what 100 % SCU speed is on this axis: the SCU actuator's (derived)
  double min_speed_mm_s = 0.5;   // below this the actuator may not move at all (checked before motion)
  double max_accel_mm_s2 = 40.0;
  double max_jerk_mm_s3 = 400.0;
  bool encoder = false;  // measured by the cell's encoder
  // The SCU target corrected while the axis moves, from the drift learnt against the encoder (a soft
  // RS, then RT and RE while the actuator still runs down): off unless the SCU is known to take that.
  bool correct_in_motion = false;
  // Following error as LinuxCNC's MIN_FERROR / FERROR: the measured position may differ from the
  // planned one by ferror_mm × |planned speed| / max_speed_mm_s, never less than min_ferror_mm.
  double min_ferror_mm = 1.0;
  double ferror_mm = 5.0;
  HomingConfig homing;  // `homing:`; strategy none when absent
};

[[nodiscard]] std::vector<AxisConfig> parse_axes(const YamlNode& list);

// The following error allowed at `planned_mm_s` (LinuxCNC's rule: linear in the speed, at least
// min_ferror_mm).
[[nodiscard]] double allowed_following_error(const AxisConfig& axis, double planned_mm_s) noexcept;

}  // namespace cellctl::config

#pragma once
// The rules that tie the cell config's sections together: every axis is an actuator the SCU has,
// moved alone by its function; its travel fits the stroke; its edges per mm agree with the SCU's;
// the encoder measures exactly one axis when there is an encoder; limits.link_silence_ms is longer than
// every device's normal spacing of replies; the encoder's velocity (and acceleration) time base can
// represent the overspeed limit (and the measured axis's acceleration) without saturating.

#include "config/yaml_node.hpp"

namespace cellctl::config {

struct CellConfig;

// Completes derived values (an axis's edges_per_mm from the SCU section) and throws ConfigError at
// the offending field otherwise.
void check_cell(const YamlNode& root, CellConfig& cell);

}  // namespace cellctl::config

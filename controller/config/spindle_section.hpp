#pragma once
// The `spindle:` section of the cell config: the converter's port, the session's timings and, for the
// emulated converter, its set-up (motor limits, ramps, identification, initial run-times).

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "spindle/emulator.hpp"
#include "spindle/session.hpp"

namespace cellctl::config {

struct SpindleSection {
  PortConfig port;
  spindle::SessionConfig session;
  spindle::EmulatorConfig emulator;
};

// Throws ConfigError (file:line:column: field: rule) on an unknown key or a value out of range.
[[nodiscard]] SpindleSection parse_spindle_section(const YamlNode& section);

}  // namespace cellctl::config

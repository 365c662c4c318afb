#pragma once
// The `spindle:` section of the cell config: the converter's port and the session's timings. Its
// `emulator:` block (the emulated converter's motor limits, ramps, identification) is allowed here and
// read by runtime/emulator_setup, where emulators are built.

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "spindle/session.hpp"

namespace cellctl::config {

struct SpindleSection {
  PortConfig port;
  spindle::SessionConfig session;
};

// Throws ConfigError (file:line:column: field: rule) on an unknown key or a value out of range.
[[nodiscard]] SpindleSection parse_spindle_section(const YamlNode& section);

}  // namespace cellctl::config

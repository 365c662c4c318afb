#pragma once
// The `encoder:` section of the cell config: the PROFIBUS port (8E1), the DP master's bus settings,
// the encoder's functionality and parameters (checked against the manual's rules here, at load time),
// and the length per count. Its `emulator:` block (the emulated encoder's resolution, serial, EEPROM
// state file) is allowed here and read by runtime/emulator_setup, where emulators are built.

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "encoder/session.hpp"

namespace cellctl::config {

struct EncoderSection {
  PortConfig port;
  encoder::SessionConfig session;
};

// Throws ConfigError (file:line:column: field: rule) on an unknown key, a value out of range or
// parameters that break one of the manual's rules (the message names the parameter and the rule).
[[nodiscard]] EncoderSection parse_encoder_section(const YamlNode& section);
// singleturn_steps and revolutions of `s` (the section, or its emulator block), `fallback` for those absent.
[[nodiscard]] encoder::PhysicalResolution parse_physical_resolution(const YamlNode& s,
                                                                    encoder::PhysicalResolution fallback);

}  // namespace cellctl::config

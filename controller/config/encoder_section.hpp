#pragma once
// The `encoder:` section of the cell config: the PROFIBUS port (8E1), the DP master's bus settings,
// the encoder's functionality and parameters (checked against the manual's rules here, at load time),
// the length per count, and for the emulated encoder its resolution, serial and EEPROM state file.

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "encoder/emulator.hpp"
#include "encoder/session.hpp"

namespace cellctl::config {

struct EncoderSection {
  PortConfig port;
  encoder::SessionConfig session;
  encoder::EmulatorConfig
      emulator;  // address and line follow the session's; the functionality is the master's choice
};

// Throws ConfigError (file:line:column: field: rule) on an unknown key, a value out of range or
// parameters that break one of the manual's rules (the message names the parameter and the rule).
[[nodiscard]] EncoderSection parse_encoder_section(const YamlNode& section);

}  // namespace cellctl::config

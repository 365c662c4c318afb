#pragma once
// The `scu:` section of the cell config: the SCU's port, the session's safety and timing, the actuators
// fitted (edges per mm, and for the emulator their physics) and the function parameterization
// (default SCP11: Fn moves actuator n). One list of actuators and functions feeds both the session and
// the emulator, so that an emulated SCU is parameterized like the real one.

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "scu/emulator_config.hpp"
#include "scu/session_config.hpp"

namespace cellctl::config {

struct ScuSection {
  PortConfig port;
  scu::SessionConfig session;
  scu::EmulatorConfig emulator;
};

// Throws ConfigError (file:line:column: field: rule) on an unknown key, a value out of range, a
// duplicate actuator, or a function that moves an actuator the section does not list.
[[nodiscard]] ScuSection parse_scu_section(const YamlNode& section);

}  // namespace cellctl::config

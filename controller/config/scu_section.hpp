#pragma once
// The `scu:` section of the cell config as the session needs it: the SCU's port, the session's safety
// and timing, the actuators fitted (edges per mm, stroke, full speed) and the function
// parameterization (default SCP11: Fn moves actuator n). The same list also describes the emulated
// SCU's physics (ramps, minimum speed, start position, scale error): those keys are allowed here and
// read by runtime/emulator_setup, where emulators are built.

#include "config/line_section.hpp"
#include "config/yaml_node.hpp"
#include "scu/session_config.hpp"

namespace cellctl::config {

struct ScuSection {
  PortConfig port;
  scu::SessionConfig session;
};

// The keys of an actuator item and of the section that only the emulator reads.
inline constexpr std::array<std::string_view, 4> kScuEmulatorActuatorKeys = {
    "ramp_mm_s2", "min_speed_mm_s", "start_position_mm", "scale_error"};

// Throws ConfigError (file:line:column: field: rule) on an unknown key, a value out of range, a
// duplicate actuator, or a function that moves an actuator the section does not list.
[[nodiscard]] ScuSection parse_scu_section(const YamlNode& section);

}  // namespace cellctl::config

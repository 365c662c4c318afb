#pragma once
// The safety monitor's rules, each with a name that appears in the journal and on the terminal.

#include <cstdint>
#include <string_view>

namespace cellctl::monitor {

enum class Rule : std::uint8_t {
  position_limit,        // an axis outside the cell's travel limits
  overspeed,             // encoder velocity above the cell's limit
  disagreement,          // SCU position and encoder position differ by more than the tolerance
  following_error,       // an axis off its planned position by more than its speed allows (LinuxCNC's FERROR)
  encoder_not_ready,     // the encoder left data exchange or dropped its Ready bit
  encoder_alarm,         // the encoder's diagnosis reports an alarm
  encoder_limit_switch,  // the encoder's limit-switch status bit
  encoder_diagnosis,     // the encoder signals new diagnosis (DH) during the run
  spindle_fault,         // the converter reports a fault
  spindle_temperature,   // motor PTC over-temperature
  spindle_frequency,     // actual frequency outside the allowed range, or off the set-point at speed
  scu_error,             // a bit in the SCU's error word
  link_silent,           // a device link silent past its deadline
  operator_stop,         // Ctrl-C or a stop command
  emergency_stop,        // an emergency stop command
};
inline constexpr std::size_t kRuleCount = 15;

[[nodiscard]] constexpr std::string_view to_string(Rule r) noexcept {
  constexpr std::string_view names[kRuleCount] = {
      "position_limit",    "overspeed",           "disagreement",         "following_error",
      "encoder_not_ready", "encoder_alarm",       "encoder_limit_switch", "encoder_diagnosis",
      "spindle_fault",     "spindle_temperature", "spindle_frequency",    "scu_error",
      "link_silent",       "operator_stop",       "emergency_stop"};
  return names[static_cast<std::size_t>(r)];
}

}  // namespace cellctl::monitor

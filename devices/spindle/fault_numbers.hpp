#pragma once
// Warning and fault numbers (statusout1, P30–P34) that this program knows by meaning. The RS232 manual
// defines the fields but not the numbers (they are in the converter's operating manual, which is not
// at hand), so these are the emulator's choices; the session only uses them to explain, never to act.

#include <cstdint>
#include <string_view>

namespace cellctl::spindle {

// Warning: the current limit is active (WARNSTROM set); the motor keeps running.
inline constexpr std::uint8_t kWarningCurrentLimit = 21;
// Fault: the motor's PTC reports over-temperature (MOTORTEMPERATUR set); the motor runs down.
inline constexpr std::uint8_t kFaultMotorOverTemperature = 31;
// Fault: a frequency set-point (P1) outside the motor's configured minimum/maximum.
inline constexpr std::uint8_t kFaultSetpointOutOfRange = 51;
// Warning: CMD System Start while P140 (start source) or P141 (set-point source) is not "SycoDrive"
// (RS232); the converter acknowledges the command and stays at rest.
inline constexpr std::uint8_t kWarningStartSourceNotRs232 = 140;

// What a known number means, or an empty view.
[[nodiscard]] constexpr std::string_view explain_fault_number(std::uint8_t n) noexcept {
  switch (n) {
    case kWarningCurrentLimit:
      return "current limit active";
    case kFaultMotorOverTemperature:
      return "motor over-temperature (PTC)";
    case kFaultSetpointOutOfRange:
      return "frequency set-point outside the motor's limits";
    case kWarningStartSourceNotRs232:
      return "start/set-point source (P140/P141) is not SycoDrive (RS232)";
    default:
      return {};
  }
}

}  // namespace cellctl::spindle

#include "scu/status_flags.hpp"

#include <array>

namespace cellctl::scu {
namespace {

constexpr bool bit(std::uint8_t b, unsigned n) noexcept {
  return ((unsigned{b} >> n) & 1u) != 0;
}
constexpr unsigned flag(bool on, unsigned n) noexcept {
  return on ? 1u << n : 0u;
}

}  // namespace

Status1 Status1::from_byte(std::uint8_t b) noexcept {
  return {bit(b, 0), bit(b, 1), bit(b, 2), bit(b, 3), bit(b, 4), bit(b, 5), bit(b, 6), bit(b, 7)};
}

std::uint8_t Status1::to_byte() const noexcept {
  return static_cast<std::uint8_t>(flag(present, 0) | flag(limit_signal, 1) | flag(switch1, 2) |
                                   flag(switch2, 3) | flag(motion_active, 4) | flag(in_position, 5) |
                                   flag(out_position, 6) | flag(stroke_recorded, 7));
}

Status2 Status2::from_byte(std::uint8_t b) noexcept {
  return {bit(b, 0), bit(b, 1), bit(b, 2)};
}

std::uint8_t Status2::to_byte() const noexcept {
  return static_cast<std::uint8_t>(flag(initialized, 0) | flag(release_retract, 1) | flag(release_extend, 2));
}

std::string_view ErrorWord::cause(int bit) noexcept {
  static constexpr std::array<std::string_view, 32> kCauses = {
      "ROM test failed",                                   // 1
      "RAM test failed",                                   // 2
      "CPU test failed",                                   // 3
      "stack overrun",                                     // 4
      "program sequence error / watchdog reset",           // 5
      "hand switch test failed",                           // 6
      "binary input test failed",                          // 7
      "relay/FET test failed",                             // 8
      "unused bit 9",                                      // 9
      "no communication with MoveEnable controller",       // 10
      "MoveEnable output check failed",                    // 11
      "over-temperature at rectifier or FET",              // 12
      "shut down: battery deeply discharged",              // 13
      "total current exceeded",                            // 14
      "actuator 1 fault",                                  // 15
      "actuator 2 fault",                                  // 16
      "actuator 3 fault",                                  // 17
      "actuator 4 fault",                                  // 18
      "actuator 5 fault",                                  // 19
      "actuator 6 fault",                                  // 20
      "position difference too great (synchronized run)",  // 21
      "remote communication time-out (watchdog)",          // 22
      "unused bit 23",                                     // 23
      "locking box I2C communication error",               // 24
      "EEPROM configuration data CRC invalid",             // 25
      "EEPROM user data CRC invalid",                      // 26
      "EEPROM locking box data CRC invalid",               // 27
      "EEPROM dynamic data CRC invalid",                   // 28
      "EEPROM calibration data CRC invalid",               // 29
      "EEPROM calibration data CRC invalid (copy)",        // 30
      "IO test failed",                                    // 31
      "motions are not executed",                          // 32
  };
  if (bit < 1 || bit > 32) return "no such bit";
  return kCauses[static_cast<std::size_t>(bit - 1)];
}

}  // namespace cellctl::scu

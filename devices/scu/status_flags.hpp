#pragma once
// The SCU's bit-coded state, decoded into named flags: actuator status 1 (0x0171..), actuator status 2
// (0x00E1..) and the 32-bit error word (0x00D1..; bits numbered from 1 = LSB, as in the manual 4.5).

#include <cstdint>
#include <string_view>

namespace cellctl::scu {

struct Status1 {
  bool present = false;          // bit 0
  bool limit_signal = false;     // bit 1: signal limit_in_out
  bool switch1 = false;          // bit 2
  bool switch2 = false;          // bit 3
  bool motion_active = false;    // bit 4
  bool in_position = false;      // bit 5: in position reached
  bool out_position = false;     // bit 6: out position reached
  bool stroke_recorded = false;  // bit 7

  [[nodiscard]] static Status1 from_byte(std::uint8_t b) noexcept;
  [[nodiscard]] std::uint8_t to_byte() const noexcept;
  friend bool operator==(const Status1&, const Status1&) = default;
};

struct Status2 {
  bool initialized = false;      // bit 0
  bool release_retract = false;  // bit 1
  bool release_extend = false;   // bit 2

  [[nodiscard]] static Status2 from_byte(std::uint8_t b) noexcept;
  [[nodiscard]] std::uint8_t to_byte() const noexcept;
};

// Error-word bit numbers the program reacts to (1-based, as printed in the manual).
namespace error_bit {
inline constexpr int kTotalCurrent = 14;
inline constexpr int kActuatorFault1 = 15;  // 15..20 for actuators 1..6
inline constexpr int kPositionDifference = 21;
inline constexpr int kRemoteTimeout = 22;
[[nodiscard]] constexpr int actuator_fault(int actuator) noexcept {
  return kActuatorFault1 + actuator - 1;
}
}  // namespace error_bit

class ErrorWord {
 public:
  constexpr ErrorWord() = default;
  constexpr explicit ErrorWord(std::uint32_t raw) noexcept : raw_(raw) {}
  [[nodiscard]] static constexpr std::uint32_t mask(int bit) noexcept {
    return std::uint32_t{1} << (bit - 1);
  }
  [[nodiscard]] constexpr bool has(int bit) const noexcept { return (raw_ & mask(bit)) != 0; }
  constexpr void set(int bit) noexcept { raw_ |= mask(bit); }
  constexpr void clear(int bit) noexcept { raw_ &= ~mask(bit); }
  [[nodiscard]] constexpr std::uint32_t raw() const noexcept { return raw_; }
  [[nodiscard]] constexpr bool any() const noexcept { return raw_ != 0; }
  // The lowest set bit (1..32), 0 with none: the cause a fault report names first.
  [[nodiscard]] constexpr int first() const noexcept {
    for (int bit = 1; bit <= 32; ++bit)
      if (has(bit)) return bit;
    return 0;
  }

  [[nodiscard]] bool over_current() const noexcept { return has(error_bit::kTotalCurrent); }
  [[nodiscard]] bool actuator_fault(int actuator) const noexcept {
    return has(error_bit::actuator_fault(actuator));
  }
  [[nodiscard]] bool position_difference() const noexcept { return has(error_bit::kPositionDifference); }
  [[nodiscard]] bool remote_timeout() const noexcept { return has(error_bit::kRemoteTimeout); }

  // Calls fn(bit, cause) for every set bit, lowest first: the named causes without allocating.
  template <class Fn>
  void for_each_cause(Fn&& fn) const {
    for (int bit = 1; bit <= 32; ++bit)
      if (has(bit)) fn(bit, cause(bit));
  }
  // The manual's cause for a bit (1..32), in short words.
  [[nodiscard]] static std::string_view cause(int bit) noexcept;

  friend constexpr bool operator==(ErrorWord, ErrorWord) = default;

 private:
  std::uint32_t raw_ = 0;
};

}  // namespace cellctl::scu

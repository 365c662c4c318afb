#pragma once
// Cyclic data (manual 4.3), big-endian: the input (position word with or without the 7 status bits,
// then signed 16-bit velocity and acceleration for Scancon 2.2/3.0) and the 32-bit output word.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>

#include "encoder/functionality.hpp"
#include "encoder/parameters.hpp"
#include "link/clock.hpp"

namespace cellctl::encoder {

// Bits of the position word (4.3.3) and of the output word (4.3–4.4).
namespace bits {
inline constexpr std::uint32_t position25 = 0x01FF'FFFFu;  // position with status bits
inline constexpr std::uint32_t position31 = 0x7FFF'FFFFu;  // position without status bits
inline constexpr std::uint32_t ready = 1u << 25;
inline constexpr std::uint32_t mode = 1u << 26;  // set = NOT in commissioning mode
inline constexpr std::uint32_t limit_switch = 1u << 27;
inline constexpr std::uint32_t code_sequence = 1u << 28;  // input: set = ccw; output: change direction
inline constexpr std::uint32_t teach_in_end = 1u << 29;
inline constexpr std::uint32_t teach_in_start = 1u << 30;
inline constexpr std::uint32_t preset = 1u << 31;
}  // namespace bits

struct StatusBits {
  bool ready = false;
  bool commissioning = false;  // bit 26 clear
  bool limit_switch = false;
  bool ccw = false;
  bool teach_in_end = false;
  bool teach_in_start = false;
  bool preset = false;
  friend bool operator==(const StatusBits&, const StatusBits&) = default;
};

struct CyclicInput {
  std::uint32_t word = 0;         // the raw position word
  std::int16_t velocity = 0;      // Scancon 2.2/3.0
  std::int16_t acceleration = 0;  // Scancon 3.0

  [[nodiscard]] std::uint32_t position(bool with_status) const noexcept {
    return word & (with_status ? bits::position25 : bits::position31);
  }
  [[nodiscard]] StatusBits status() const noexcept;
  friend bool operator==(const CyclicInput&, const CyclicInput&) = default;
};

enum class CyclicError : std::uint8_t { bad_length, bit31_set };
[[nodiscard]] std::string_view to_string(CyclicError e) noexcept;

// Input of the given functionality; without status bits bit 31 must be 0 (4.3.1/4.3.5).
[[nodiscard]] std::variant<CyclicInput, CyclicError> decode_input(
    Functionality f, bool with_status, std::span<const std::uint8_t> bytes) noexcept;
std::size_t encode_input(Functionality f, const CyclicInput& in, std::span<std::uint8_t> out) noexcept;

[[nodiscard]] std::optional<std::uint32_t> decode_output(std::span<const std::uint8_t> bytes) noexcept;
std::size_t encode_output(std::uint32_t word, std::span<std::uint8_t> out) noexcept;

// 16-bit velocity/acceleration saturate at the extremes (4.3.4/4.3.5): 32767 / −32768 mean
// "at least this much", not a measurement.
[[nodiscard]] constexpr bool saturated(std::int16_t v) noexcept {
  return v == INT16_MAX || v == INT16_MIN;
}
[[nodiscard]] std::int16_t saturate16(double v) noexcept;

// The sample time of a time base: 1 s, 100 ms, 10 ms; RPM is counted over 1 s and scaled to a minute.
[[nodiscard]] link::Duration sample_period(TimeBase tb) noexcept;
// A velocity (or acceleration, per sample period) in its time base → measuring units per second.
[[nodiscard]] double units_per_second(double value, TimeBase tb, double units_per_revolution) noexcept;
// Units per second → the time base's unit (inverse of units_per_second).
[[nodiscard]] double in_time_base(double units_per_s, TimeBase tb, double units_per_revolution) noexcept;

}  // namespace cellctl::encoder

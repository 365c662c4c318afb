#pragma once
// The UART character framing of a serial line: what SerialLink programs into termios and what
// SimLink uses to decide how long each byte takes on the wire.

#include <cstdint>
#include <string>

#include "link/clock.hpp"

namespace cellctl::link {

enum class Parity : std::uint8_t { none, even, odd };

struct LineFormat {
  std::uint32_t baud = 38400;
  std::uint8_t data_bits = 8;
  Parity parity = Parity::none;
  std::uint8_t stop_bits = 1;

  // Start bit + data + parity + stop: 10 for 8N1, 11 for PROFIBUS's 8E1.
  [[nodiscard]] std::uint32_t bits_per_char() const noexcept {
    return 1u + data_bits + (parity == Parity::none ? 0u : 1u) + stop_bits;
  }
  // The time one character occupies the line.
  [[nodiscard]] Duration char_time() const noexcept {
    return Duration{static_cast<Duration::rep>(1'000'000'000ull * bits_per_char() / baud)};
  }
  // "38400 8N1"
  [[nodiscard]] std::string describe() const;
};

[[nodiscard]] constexpr LineFormat line_8n1(std::uint32_t baud) noexcept {
  return {baud, 8, Parity::none, 1};
}
[[nodiscard]] constexpr LineFormat line_8e1(std::uint32_t baud) noexcept {
  return {baud, 8, Parity::even, 1};
}

}  // namespace cellctl::link

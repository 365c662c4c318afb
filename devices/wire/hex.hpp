#pragma once
// Hex text for bytes: the trace's "52 4f 00" form, lowercase digits for the spindle's ASCII-hex
// telegrams, and parsing of hex text in tests and commissioning commands.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cellctl::wire {

// "52 4f 00" — lowercase, one space between bytes.
[[nodiscard]] std::string to_hex(std::span<const std::uint8_t> bytes);

// The lowercase ASCII digit for a nibble 0..15.
[[nodiscard]] constexpr char hex_digit(unsigned nibble) noexcept {
  return "0123456789abcdef"[nibble & 0xFu];
}

// The value of one ASCII hex digit (either case), or -1 when it is none.
[[nodiscard]] constexpr int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Parses hex text, ignoring spaces ("52 4f 00", "524f00"); nullopt on an odd count or a bad digit.
[[nodiscard]] std::optional<std::vector<std::uint8_t>> parse_hex(std::string_view text);

}  // namespace cellctl::wire

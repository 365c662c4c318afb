#pragma once
// The five functionalities of the SCH88BEX (manual 4, table "Designation"): what each one exchanges
// cyclically, how long its User_Prm_Data is, and the DP configuration identifiers we define for it
// (no GSD ships with the manual; devices/encoder/gsd/SCAN88EX.gsd declares the same bytes).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace cellctl::encoder {

enum class Functionality : std::uint8_t { class1, class2, scancon21, scancon22, scancon30 };
inline constexpr std::array<Functionality, 5> kFunctionalities = {
    Functionality::class1, Functionality::class2, Functionality::scancon21, Functionality::scancon22,
    Functionality::scancon30};

// Our PROFIBUS ident number for the emulated encoder (also in the GSD file).
inline constexpr std::uint16_t kIdentNumber = 0x0C88;

[[nodiscard]] constexpr bool is_scancon(Functionality f) noexcept {
  return f == Functionality::scancon21 || f == Functionality::scancon22 || f == Functionality::scancon30;
}
[[nodiscard]] constexpr bool has_outputs(Functionality f) noexcept {
  return f != Functionality::class1;
}

// Manual 4.3: 0/4 output bytes; 4, 6 (+ velocity) or 8 (+ acceleration) input bytes.
[[nodiscard]] constexpr std::size_t output_length(Functionality f) noexcept {
  return has_outputs(f) ? 4 : 0;
}
[[nodiscard]] constexpr std::size_t input_length(Functionality f) noexcept {
  switch (f) {
    case Functionality::scancon22:
      return 6;
    case Functionality::scancon30:
      return 8;
    default:
      return 4;
  }
}

// User_Prm_Data from octet 8 (reserved, 0x00 in DP-V0): Class 1 up to octet 9, Class 2 up to
// octet 25 (18–25 reserved), the Scancon functionalities up to octet 39.
[[nodiscard]] constexpr std::size_t user_prm_length(Functionality f) noexcept {
  if (f == Functionality::class1) return 2;
  if (f == Functionality::class2) return 18;
  return 32;
}

// Extended diagnosis length including its header (4.2.1): 10 for Class 1 and for the short option,
// 51 otherwise (16 / 57 octets with the 6 standard ones).
inline constexpr std::size_t kExtDiagShort = 10;
inline constexpr std::size_t kExtDiagLong = 51;

// Configuration identifiers. Class 1/2 use the encoder profile's general identifiers (0xD1: 2 input
// words consistent; 0xF1: 2 input + 2 output words consistent). The Scancon modes use the special
// format with one manufacturer byte naming the mode, so that a master configured for another mode
// is refused with Cfg_Fault instead of exchanging data of the wrong shape: header 0xC1 (output and
// input length bytes follow, 1 manufacturer byte), output length 0xC1 (2 words consistent), input
// length 0xC1/0xC2/0xC3 (2/3/4 words consistent), manufacturer byte 0x21/0x22/0x30.
inline constexpr std::array<std::uint8_t, 1> kCfgClass1 = {0xD1};
inline constexpr std::array<std::uint8_t, 1> kCfgClass2 = {0xF1};
inline constexpr std::array<std::uint8_t, 4> kCfgScancon21 = {0xC1, 0xC1, 0xC1, 0x21};
inline constexpr std::array<std::uint8_t, 4> kCfgScancon22 = {0xC1, 0xC1, 0xC2, 0x22};
inline constexpr std::array<std::uint8_t, 4> kCfgScancon30 = {0xC1, 0xC1, 0xC3, 0x30};

[[nodiscard]] constexpr std::span<const std::uint8_t> config_identifiers(Functionality f) noexcept {
  switch (f) {
    case Functionality::class1:
      return kCfgClass1;
    case Functionality::class2:
      return kCfgClass2;
    case Functionality::scancon21:
      return kCfgScancon21;
    case Functionality::scancon22:
      return kCfgScancon22;
    case Functionality::scancon30:
      return kCfgScancon30;
  }
  return {};
}

// The functionality whose configuration identifiers these are (what a master's Chk_Cfg selects).
[[nodiscard]] constexpr std::optional<Functionality> functionality_of_cfg(
    std::span<const std::uint8_t> cfg) noexcept {
  for (const Functionality f : kFunctionalities)
    if (std::ranges::equal(cfg, config_identifiers(f))) return f;
  return std::nullopt;
}

[[nodiscard]] constexpr std::string_view to_string(Functionality f) noexcept {
  switch (f) {
    case Functionality::class1:
      return "class1";
    case Functionality::class2:
      return "class2";
    case Functionality::scancon21:
      return "scancon2.1";
    case Functionality::scancon22:
      return "scancon2.2";
    case Functionality::scancon30:
      return "scancon3.0";
  }
  return "?";
}

}  // namespace cellctl::encoder

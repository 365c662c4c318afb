#pragma once
// The encoder's parameterisation (manual 4.1) as a typed set, its User_Prm_Data bytes (octet 8
// reserved 0x00, octet 9 Operating Parameters 1 onwards, multi-byte values big-endian) and the
// manual's rules. decode_user_prm() checks what the bytes alone can break (lengths, bits that must
// be 0 or 1, reserved octets); validate() checks the rules against the physical resolution. The
// emulator refuses with Prm_Fault on either; the session runs validate() before it sends anything.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "encoder/functionality.hpp"

namespace cellctl::encoder {

enum class CodeSequence : std::uint8_t { cw = 0, ccw = 1 };  // increasing clockwise / counterclockwise
// Octet 26 bits 0–1 (4.1.5). The fourth value 0b11 is not valid.
enum class UnitsSelect : std::uint8_t { per_revolution = 0, per_total_range = 1, per_physical_impulses = 2 };
// Octet 39 bits 4–5 (4.1.9).
enum class TimeBase : std::uint8_t { steps_per_s = 0, steps_per_100ms = 1, steps_per_10ms = 2, rpm = 3 };

// The encoder as delivered: 2^n steps per revolution, 2^m revolutions (manual 6: n ≤ 16, m ≤ 15).
struct PhysicalResolution {
  std::uint32_t steps_per_revolution = 8192;
  std::uint32_t revolutions = 4096;
  [[nodiscard]] std::uint64_t total() const noexcept {
    return std::uint64_t{steps_per_revolution} * std::uint64_t{revolutions};
  }
};

struct EncoderParameters {
  Functionality functionality = Functionality::scancon22;
  CodeSequence code_sequence = CodeSequence::cw;           // octet 9 bit 0
  bool scaling = false;                                    // octet 9 bit 3
  std::uint32_t measuring_units = 4096;                    // octets 10–13 (per rev. / desired units)
  std::uint32_t total_range = 16777216;                    // octets 14–17
  UnitsSelect units_select = UnitsSelect::per_revolution;  // octet 26 bits 0–1
  bool commissioning = false;                              // octet 26 bit 2
  bool short_diagnosis = false;                            // octet 26 bit 3
  bool without_status_bits = false;                        // octet 26 bit 4 (Scancon 3.0 only)
  bool lower_limit_enabled = false;                        // octet 26 bit 5
  bool upper_limit_enabled = false;                        // octet 26 bit 6
  std::uint32_t lower_limit = 0;                           // octets 27–30
  std::uint32_t upper_limit = 32767;                       // octets 31–34
  std::uint32_t physical_impulses = 4096;                  // octets 35–38
  bool multiturn = true;                                   // octet 39 bit 1
  TimeBase time_base = TimeBase::steps_per_s;              // octet 39 bits 4–5
  // Not on the wire: the axis crosses the physical zero point (4.1.3 rule 2). Only the master knows.
  bool endless = false;

  friend bool operator==(const EncoderParameters&, const EncoderParameters&) = default;
};

// A broken rule: which parameter (named as in the manual) and what the rule says. value/limit are
// the offending number and the bound it broke, where there is one.
struct PrmViolation {
  std::string_view parameter;
  std::string_view rule;
  std::uint64_t value = 0;
  std::uint64_t limit = 0;
  // "Total Measuring Range: must not exceed the physical range 2^(n+m) (value 40000000, limit 33554432)"
  [[nodiscard]] std::string describe() const;
  friend bool operator==(const PrmViolation&, const PrmViolation&) = default;
};

// Writes user_prm_length(p.functionality) bytes; returns the number written, 0 if `out` is too small.
std::size_t encode_user_prm(const EncoderParameters& p, std::span<std::uint8_t> out) noexcept;

// The typed set, or the first rule the bytes break. `endless` comes back false.
[[nodiscard]] std::variant<EncoderParameters, PrmViolation> decode_user_prm(
    Functionality f, std::span<const std::uint8_t> bytes) noexcept;

// The manual's rules against the physical resolution (4.1.2–4.1.9, 4.3.3); nullopt when all hold.
[[nodiscard]] std::optional<PrmViolation> validate(const EncoderParameters& p,
                                                   const PhysicalResolution& phys) noexcept;

// The physical resolution's own limits (manual 6): powers of two, ≤ 2^16 steps, ≤ 2^15 revolutions.
[[nodiscard]] std::optional<PrmViolation> validate(const PhysicalResolution& phys) noexcept;

// Whether the position is sent with the 7 status bits (Scancon modes unless "without status bits").
[[nodiscard]] constexpr bool has_status_bits(const EncoderParameters& p) noexcept {
  return is_scancon(p.functionality) && !p.without_status_bits;
}

}  // namespace cellctl::encoder

#pragma once
// The encoder's extended diagnosis (manual 4.2): the part of Slave_Diag from octet 7 (header) on,
// 10 octets for Class 1 and the short option (16 with the standard six), 51 otherwise (57).
// Multi-byte values big-endian.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>

namespace cellctl::encoder {

// Octet 8 (4.2.2) and octets 18–19 (4.2.8).
namespace alarm {
inline constexpr std::uint16_t position_error = 1u << 0;
inline constexpr std::uint16_t supply_voltage = 1u << 1;
inline constexpr std::uint16_t current_too_high = 1u << 2;
inline constexpr std::uint16_t commissioning_diagnostics = 1u << 3;
inline constexpr std::uint16_t memory_error = 1u << 4;
// What the SCH88BEX supports (4.2.8).
inline constexpr std::uint16_t supported = position_error | supply_voltage;
}  // namespace alarm

// Octets 20–21 (4.2.9) and 22–23 (4.2.10).
namespace warning {
inline constexpr std::uint16_t frequency_exceeded = 1u << 0;
inline constexpr std::uint16_t temperature_exceeded = 1u << 1;
inline constexpr std::uint16_t light_control_reserve = 1u << 2;
inline constexpr std::uint16_t cpu_watchdog = 1u << 3;
inline constexpr std::uint16_t operating_time_limit = 1u << 4;
inline constexpr std::uint16_t battery_charge = 1u << 5;
inline constexpr std::uint16_t reference_point = 1u << 6;
inline constexpr std::uint16_t supported =
    temperature_exceeded | light_control_reserve | operating_time_limit | battery_charge;
}  // namespace warning

// Octet 9 (4.2.3).
struct OperatingStatus {
  bool ccw = false;                        // bit 0: increasing counterclockwise
  bool class2 = false;                     // bit 1
  bool commissioning_diagnostics = false;  // bit 2
  bool scaling = false;                    // bit 3
  friend bool operator==(const OperatingStatus&, const OperatingStatus&) = default;
};

struct Version {
  std::uint8_t major = 0;
  std::uint8_t minor = 0;
  friend bool operator==(const Version&, const Version&) = default;
};

// Octets 17–57, present in the 51-octet form only.
struct DiagnosisDetail {
  std::uint8_t additional_alarms = 0;        // 17
  std::uint16_t supported_alarms = 0;        // 18–19
  std::uint16_t warnings = 0;                // 20–21
  std::uint16_t supported_warnings = 0;      // 22–23
  Version profile_version;                   // 24–25
  Version software_version;                  // 26–27
  std::uint32_t operating_time_tenth_h = 0;  // 28–31, 0.1 h
  std::int32_t offset = 0;                   // 32–35, signed, measuring units
  std::int32_t manufacturer_offset = 0;      // 36–39
  std::uint32_t units_per_revolution = 0;    // 40–43
  std::uint32_t total_range = 0;             // 44–47
  std::array<char, 10> serial{};             // 48–57, ASCII ("**********" on the SCH88BEX)
  friend bool operator==(const DiagnosisDetail&, const DiagnosisDetail&) = default;
};

struct EncoderDiagnosis {
  std::uint8_t alarms = 0;                  // octet 8
  OperatingStatus status;                   // octet 9
  std::uint8_t encoder_type = 1;            // octet 10: 0 singleturn, 1 multiturn
  std::uint32_t singleturn_resolution = 0;  // 11–14
  std::uint16_t revolutions = 0;            // 15–16
  std::optional<DiagnosisDetail> detail;    // the long form

  [[nodiscard]] std::size_t length() const noexcept;  // 10 or 51, header included
  [[nodiscard]] bool multiturn() const noexcept { return encoder_type == 1; }
  friend bool operator==(const EncoderDiagnosis&, const EncoderDiagnosis&) = default;
};

enum class DiagError : std::uint8_t { bad_length, header_mismatch, unassigned_bits_set };
[[nodiscard]] std::string_view to_string(DiagError e) noexcept;

// `ext` starts at octet 7 (the header). Decodes either length; anything else is a typed error.
[[nodiscard]] std::variant<EncoderDiagnosis, DiagError> decode_diagnosis(
    std::span<const std::uint8_t> ext) noexcept;
// Writes d.length() octets; returns the count, 0 when `out` is too small.
std::size_t encode_diagnosis(const EncoderDiagnosis& d, std::span<std::uint8_t> out) noexcept;

}  // namespace cellctl::encoder

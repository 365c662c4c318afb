#include "encoder/parameters.hpp"

#include <fmt/format.h>

#include <bit>

#include "encoder/scaling.hpp"
#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::encoder {
namespace {

constexpr std::uint8_t bit(unsigned n) noexcept {
  return static_cast<std::uint8_t>(1u << n);
}
constexpr std::uint64_t kStatusBitsRange = std::uint64_t{1} << 25;  // 4.3.3: 25-bit position
constexpr std::uint64_t kPlainRange = std::uint64_t{1} << 31;       // 4.3.1: 31 bits used

PrmViolation violation(std::string_view parameter, std::string_view rule, std::uint64_t value = 0,
                       std::uint64_t limit = 0) noexcept {
  return PrmViolation{parameter, rule, value, limit};
}

std::optional<PrmViolation> in_range(std::string_view parameter, std::string_view rule, std::uint64_t value,
                                     std::uint64_t min, std::uint64_t max) noexcept {
  if (value < min) return violation(parameter, rule, value, min);
  if (value > max) return violation(parameter, rule, value, max);
  return std::nullopt;
}

std::optional<PrmViolation> check_scaling(const EncoderParameters& p,
                                          const PhysicalResolution& phys) noexcept {
  const bool per_revolution =
      p.functionality == Functionality::class2 || p.units_select == UnitsSelect::per_revolution;
  if (per_revolution) {
    const std::string_view name = p.functionality == Functionality::class2 ? "Measuring Units per Revolution"
                                                                           : "Desired Measuring Units";
    if (auto v = in_range(name, "must be 1 … the physical steps per revolution 2^n (4.1.2)",
                          p.measuring_units, 1, phys.steps_per_revolution))
      return v;
    if (auto v = in_range("Total Measuring Range", "must be 1 … the physical range 2^(n+m) (4.1.3)",
                          p.total_range, 1, phys.total()))
      return v;
    if (p.total_range % p.measuring_units != 0)
      return violation("Total Measuring Range",
                       "must be an integer multiple of the measuring units per revolution (4.1.3 rule 1)",
                       p.total_range, p.measuring_units);
    if (p.endless && !std::has_single_bit(p.measuring_units))
      return violation(name, "must be a power of 2 for endless operation (4.1.3 rule 2)", p.measuring_units);
    if (p.endless && !std::has_single_bit(p.total_range))
      return violation("Total Measuring Range", "must be a power of 2 for endless operation (4.1.3 rule 2)",
                       p.total_range);
    return std::nullopt;
  }
  if (auto v = in_range("Desired Measuring Units", "must be 1 … the physical range 2^(n+m) (4.1.2)",
                        p.measuring_units, 1, phys.total()))
    return v;
  if (p.units_select == UnitsSelect::per_physical_impulses)
    return in_range("Physical Impulses", "must be 1 … the physical range 2^(n+m) (4.1.8)",
                    p.physical_impulses, 1, phys.total());
  return std::nullopt;
}

std::optional<PrmViolation> check_scancon(const EncoderParameters& p,
                                          const PhysicalResolution& phys) noexcept {
  if (p.without_status_bits) {
    if (p.commissioning)
      return violation("Commissioning Mode Enable", "not possible without status bits (4.1.5 bit 4)");
    if (p.lower_limit_enabled || p.upper_limit_enabled)
      return violation("Enable Lower/Upper Limit Switch",
                       "limit switches cannot be selected without status bits (4.1.5 bit 4)");
  }
  if (p.lower_limit_enabled) {
    if (auto v = in_range("Lower Limit Switch", "must be 0 … 2^(n+m) − 1 (4.1.6)", p.lower_limit, 0,
                          phys.total() - 1))
      return v;
  }
  if (p.upper_limit_enabled) {
    if (auto v = in_range("Upper Limit Switch", "must be 1 … 2^(n+m) − 1 (4.1.7)", p.upper_limit, 1,
                          phys.total() - 1))
      return v;
  }
  if (p.lower_limit_enabled && p.upper_limit_enabled && p.lower_limit >= p.upper_limit)
    return violation("Lower Limit Switch", "must be below the upper limit switch", p.lower_limit,
                     p.upper_limit);
  if (p.multiturn != (phys.revolutions > 1))
    return violation("Encoder Type", "must match the encoder (octet 39 bit 1: 1 = multiturn)",
                     p.multiturn ? 1 : 0, phys.revolutions > 1 ? 1 : 0);
  return std::nullopt;
}

}  // namespace

std::string PrmViolation::describe() const {
  if (value == 0 && limit == 0) return fmt::format("{}: {}", parameter, rule);
  return fmt::format("{}: {} (value {}, limit {})", parameter, rule, value, limit);
}

std::size_t encode_user_prm(const EncoderParameters& p, std::span<std::uint8_t> out) noexcept {
  const std::size_t n = user_prm_length(p.functionality);
  if (out.size() < n) return 0;
  wire::ByteWriter w(out.first(n));
  w.u8(0x00);  // octet 8: DP-V0 reserved
  std::uint8_t op1 = p.code_sequence == CodeSequence::ccw ? bit(0) : 0;
  if (p.functionality != Functionality::class1) {
    op1 = static_cast<std::uint8_t>(op1 | bit(1) | (p.scaling ? bit(3) : 0));
    if (is_scancon(p.functionality)) op1 = static_cast<std::uint8_t>(op1 | bit(6));
  }
  w.u8(op1);
  if (p.functionality == Functionality::class1) return w.size();
  w.be(p.measuring_units);
  w.be(p.total_range);
  for (int i = 0; i < 8; ++i) w.u8(0x00);  // octets 18–25: reserved for future use
  if (!is_scancon(p.functionality)) return w.size();
  w.u8(static_cast<std::uint8_t>(static_cast<unsigned>(p.units_select) | (p.commissioning ? bit(2) : 0u) |
                                 (p.short_diagnosis ? bit(3) : 0u) | (p.without_status_bits ? bit(4) : 0u) |
                                 (p.lower_limit_enabled ? bit(5) : 0u) |
                                 (p.upper_limit_enabled ? bit(6) : 0u) | bit(7)));
  w.be(p.lower_limit);
  w.be(p.upper_limit);
  w.be(p.physical_impulses);
  w.u8(static_cast<std::uint8_t>((p.multiturn ? bit(1) : 0u) | (static_cast<unsigned>(p.time_base) << 4)));
  return w.ok() ? w.size() : 0;
}

std::variant<EncoderParameters, PrmViolation> decode_user_prm(Functionality f,
                                                              std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.size() != user_prm_length(f))
    return violation("User_Prm_Data", "length must match the functionality (octets 8–9 / 8–25 / 8–39)",
                     bytes.size(), user_prm_length(f));
  wire::ByteReader r(bytes);
  EncoderParameters p;
  p.functionality = f;
  if (r.u8() != 0x00) return violation("Octet 8", "reserved in DP-V0, must be 0x00");
  const std::uint8_t op1 = r.u8();
  p.code_sequence = (op1 & bit(0)) != 0 ? CodeSequence::ccw : CodeSequence::cw;
  const bool class2_bit = (op1 & bit(1)) != 0;
  if (f != Functionality::class1 && !class2_bit)
    return violation("Class 2 Functionality", "must be 1 for Class 2 and above (4.1.1 bit 1)");
  if (f == Functionality::class1 && (op1 & (bit(1) | bit(3))) != 0)
    return violation("Operating Parameters 1", "Class 1 has only the code sequence: bits 1 and 3 must be 0");
  if ((op1 & bit(2)) != 0)
    return violation("Commissioning Diagnostics", "not supported, must be 0 (4.1.1 bit 2)");
  if ((op1 & (bit(4) | bit(5) | bit(7))) != 0)
    return violation("Operating Parameters 1", "bits 4, 5 and 7 are not assigned, must be 0");
  if (((op1 & bit(6)) != 0) != is_scancon(f))
    return violation("Activate Octet 26", "must be 1 exactly for the Scancon functionalities (4.1.1 bit 6)");
  p.scaling = (op1 & bit(3)) != 0;
  if (f == Functionality::class1) {
    p.scaling = false;
    return p;
  }
  p.measuring_units = r.be<std::uint32_t>();
  p.total_range = r.be<std::uint32_t>();
  for (int i = 0; i < 8; ++i)
    if (r.u8() != 0) return violation("Octets 18–25", "reserved for future use, must be 0 (4.1.4)");
  if (!is_scancon(f)) return p;
  const std::uint8_t op2 = r.u8();
  if ((op2 & 0x03u) == 0x03u)
    return violation("Desired Measuring Units Select", "must be 0b00, 0b01 or 0b10 (4.1.5 bits 0–1)", 3, 2);
  p.units_select = static_cast<UnitsSelect>(op2 & 0x03u);
  p.commissioning = (op2 & bit(2)) != 0;
  p.short_diagnosis = (op2 & bit(3)) != 0;
  p.without_status_bits = (op2 & bit(4)) != 0;
  if (p.without_status_bits && f != Functionality::scancon30)
    return violation("Without Status Bits", "only with the Scancon 3.0 functionality (4.1.5 bit 4)");
  p.lower_limit_enabled = (op2 & bit(5)) != 0;
  p.upper_limit_enabled = (op2 & bit(6)) != 0;
  if ((op2 & bit(7)) == 0)
    return violation("Activate Octets 27–39", "must be 1 for the Scancon functionalities");
  p.lower_limit = r.be<std::uint32_t>();
  p.upper_limit = r.be<std::uint32_t>();
  p.physical_impulses = r.be<std::uint32_t>();
  const std::uint8_t op3 = r.u8();
  if ((op3 & (bit(0) | bit(2) | bit(3) | bit(6) | bit(7))) != 0)
    return violation("Operating Parameters 3", "bits 0, 2, 3, 6 and 7 are not assigned, must be 0");
  p.multiturn = (op3 & bit(1)) != 0;
  p.time_base = static_cast<TimeBase>((op3 >> 4) & 0x03u);
  return p;
}

std::optional<PrmViolation> validate(const PhysicalResolution& phys) noexcept {
  if (!std::has_single_bit(phys.steps_per_revolution) || phys.steps_per_revolution > (1u << 16))
    return violation("Singleturn Resolution", "must be a power of 2, at most 2^16 (manual 6)",
                     phys.steps_per_revolution, 1u << 16);
  if (!std::has_single_bit(phys.revolutions) || phys.revolutions > (1u << 15))
    return violation("Number of Revolutions", "must be a power of 2, at most 2^15 (manual 6)",
                     phys.revolutions, 1u << 15);
  return std::nullopt;
}

std::optional<PrmViolation> validate(const EncoderParameters& p, const PhysicalResolution& phys) noexcept {
  if (auto v = validate(phys)) return v;
  if (p.functionality == Functionality::class1) return std::nullopt;
  if (p.scaling) {
    if (auto v = check_scaling(p, phys)) return v;
  }
  if (is_scancon(p.functionality)) {
    if (auto v = check_scancon(p, phys)) return v;
  }
  const std::uint64_t range = Scaling(p, phys).range();
  if (has_status_bits(p) && range > kStatusBitsRange)
    return violation(
        "Total Measuring Range",
        "with status bits the position must fit in 25 bits: range in measuring units ≤ 2^25 (4.3.3)", range,
        kStatusBitsRange);
  if (range > kPlainRange)
    return violation("Total Measuring Range", "the position must fit in 31 bits (4.3.1)", range, kPlainRange);
  return std::nullopt;
}

}  // namespace cellctl::encoder

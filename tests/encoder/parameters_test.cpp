// User_Prm_Data bytes and every parameter rule of manual 4.1.
#include "encoder/parameters.hpp"

#include <gtest/gtest.h>

#include <array>
#include <variant>

#include "wire/hex.hpp"

namespace cellctl::encoder {
namespace {

const PhysicalResolution kPhys{8192, 4096};  // 13 + 12 bits = 2^25

EncoderParameters scancon(Functionality f = Functionality::scancon22) {
  EncoderParameters p;
  p.functionality = f;
  return p;
}

std::vector<std::uint8_t> encode(const EncoderParameters& p) {
  std::array<std::uint8_t, 64> buf{};
  const std::size_t n = encode_user_prm(p, buf);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

PrmViolation broken(const EncoderParameters& p) {
  auto v = validate(p, kPhys);
  EXPECT_TRUE(v.has_value());
  return v.value_or(PrmViolation{});
}

TEST(UserPrm, Class1IsReservedOctetAndCodeSequence) {
  EncoderParameters p = scancon(Functionality::class1);
  p.code_sequence = CodeSequence::ccw;
  EXPECT_EQ(encode(p), (std::vector<std::uint8_t>{0x00, 0x01}));
}

TEST(UserPrm, Class2BytesBigEndianWithReservedOctets) {
  EncoderParameters p = scancon(Functionality::class2);
  p.scaling = true;
  p.measuring_units = 4096;
  p.total_range = 16777216;
  EXPECT_EQ(wire::to_hex(encode(p)), "00 0a 00 00 10 00 01 00 00 00 00 00 00 00 00 00 00 00");
}

TEST(UserPrm, ScanconBytesOctets8To39) {
  EncoderParameters p = scancon(Functionality::scancon30);
  p.code_sequence = CodeSequence::ccw;
  p.scaling = true;
  p.measuring_units = 1000;
  p.total_range = 0x00010000;
  p.units_select = UnitsSelect::per_total_range;
  p.commissioning = true;
  p.short_diagnosis = true;
  p.lower_limit_enabled = true;
  p.upper_limit_enabled = true;
  p.lower_limit = 0x01020304;
  p.upper_limit = 0x05060708;
  p.physical_impulses = 4096;
  p.time_base = TimeBase::rpm;
  // octet 9 = 0x4b (bits 0,1,3,6); 26 = 0xed (01, bit 2, 3, 5, 6, 7); 39 = 0x32 (bit 1, time base 11)
  EXPECT_EQ(
      wire::to_hex(encode(p)),
      "00 4b 00 00 03 e8 00 01 00 00 00 00 00 00 00 00 00 00 ed 01 02 03 04 05 06 07 08 00 00 10 00 32");
}

TEST(UserPrm, RoundTripsEveryFunctionality) {
  for (auto f : {Functionality::class1, Functionality::class2, Functionality::scancon21,
                 Functionality::scancon22, Functionality::scancon30}) {
    EncoderParameters p = scancon(f);
    if (f != Functionality::class1) p.scaling = true;
    if (is_scancon(f)) {
      p.units_select = UnitsSelect::per_physical_impulses;
      p.time_base = f == Functionality::scancon21 ? TimeBase::steps_per_s : TimeBase::steps_per_10ms;
      p.upper_limit_enabled = true;
    }
    const auto bytes = encode(p);
    ASSERT_EQ(bytes.size(), user_prm_length(f));
    auto back = decode_user_prm(f, bytes);
    ASSERT_TRUE(std::holds_alternative<EncoderParameters>(back)) << std::get<PrmViolation>(back).describe();
    if (f == Functionality::class1)
      p = EncoderParameters{.functionality = f, .code_sequence = p.code_sequence};
    EXPECT_EQ(std::get<EncoderParameters>(back), p) << to_string(f);
  }
}

// Every rule the bytes alone can break.
struct ByteRule {
  Functionality f;
  std::size_t index;  // into User_Prm_Data (0 = octet 8)
  std::uint8_t value;
  std::string_view parameter;
};

TEST(UserPrm, DecodeRefusesBitsThatMustBeZeroOrOne) {
  const ByteRule rules[] = {
      {Functionality::scancon22, 0, 0x01, "Octet 8"},
      {Functionality::class2, 1, 0x08, "Class 2 Functionality"},      // bit 1 clear
      {Functionality::class1, 1, 0x02, "Operating Parameters 1"},     // class 2 bit in class 1
      {Functionality::class2, 1, 0x06, "Commissioning Diagnostics"},  // bit 2
      {Functionality::class2, 1, 0x12, "Operating Parameters 1"},     // bit 4
      {Functionality::class2, 1, 0x22, "Operating Parameters 1"},     // bit 5
      {Functionality::class2, 1, 0x82, "Operating Parameters 1"},     // bit 7
      {Functionality::class2, 1, 0x42, "Activate Octet 26"},          // bit 6 in class 2
      {Functionality::scancon21, 1, 0x02, "Activate Octet 26"},       // bit 6 missing
      {Functionality::class2, 10, 0x01, "Octets 18–25"},
      {Functionality::scancon21, 17, 0x01, "Octets 18–25"},
      {Functionality::scancon21, 18, 0x83, "Desired Measuring Units Select"},
      {Functionality::scancon22, 18, 0x90, "Without Status Bits"},  // only 3.0
      {Functionality::scancon30, 18, 0x00, "Activate Octets 27–39"},
      {Functionality::scancon30, 31, 0x03, "Operating Parameters 3"},  // bit 0
      {Functionality::scancon30, 31, 0x06, "Operating Parameters 3"},  // bit 2
      {Functionality::scancon30, 31, 0x82, "Operating Parameters 3"},  // bit 7
  };
  for (const auto& rule : rules) {
    auto bytes = encode(scancon(rule.f));
    bytes[rule.index] = rule.value;
    auto r = decode_user_prm(rule.f, bytes);
    ASSERT_TRUE(std::holds_alternative<PrmViolation>(r)) << rule.parameter << " index " << rule.index;
    EXPECT_EQ(std::get<PrmViolation>(r).parameter, rule.parameter) << "index " << rule.index;
  }
}

TEST(UserPrm, DecodeRefusesWrongLength) {
  auto bytes = encode(scancon(Functionality::scancon21));
  bytes.pop_back();
  auto r = decode_user_prm(Functionality::scancon21, bytes);
  ASSERT_TRUE(std::holds_alternative<PrmViolation>(r));
  EXPECT_EQ(std::get<PrmViolation>(r).parameter, "User_Prm_Data");
  EXPECT_EQ(std::get<PrmViolation>(r).limit, 32u);
}

TEST(Validate, DefaultsAreValidForEveryFunctionality) {
  for (auto f : {Functionality::class1, Functionality::class2, Functionality::scancon21,
                 Functionality::scancon22, Functionality::scancon30})
    EXPECT_FALSE(validate(scancon(f), kPhys).has_value()) << to_string(f);
}

TEST(Validate, UnitsPerRevolutionAtMostPhysicalSteps) {
  EncoderParameters p = scancon(Functionality::class2);
  p.scaling = true;
  p.measuring_units = 8192;
  p.total_range = 8192 * 16;
  EXPECT_FALSE(validate(p, kPhys));
  p.measuring_units = 8193;
  const auto v = broken(p);
  EXPECT_EQ(v.parameter, "Measuring Units per Revolution");
  EXPECT_EQ(v.limit, 8192u);
  EXPECT_EQ(v.describe(),
            "Measuring Units per Revolution: must be 1 … the physical steps per revolution 2^n (4.1.2) "
            "(value 8193, "
            "limit 8192)");
  p.measuring_units = 0;
  EXPECT_EQ(broken(p).parameter, "Measuring Units per Revolution");
}

TEST(Validate, ScalingOffIgnoresScalingParameters) {
  EncoderParameters p = scancon(Functionality::class2);
  p.measuring_units = 999999;  // "ignored regardless of their value" (4.1.1 bit 3)
  p.total_range = 7;
  EXPECT_FALSE(validate(p, kPhys));
}

TEST(Validate, TotalRangeAtMostPhysicalRange) {
  EncoderParameters p = scancon(Functionality::class2);
  p.scaling = true;
  p.measuring_units = 1;
  p.total_range = (1u << 25) + 1;
  const auto v = broken(p);
  EXPECT_EQ(v.parameter, "Total Measuring Range");
  EXPECT_EQ(v.limit, 1u << 25);
}

TEST(Validate, TotalRangeIntegerMultipleOfUnitsPerRevolution) {
  EncoderParameters p = scancon(Functionality::scancon21);
  p.scaling = true;
  p.measuring_units = 3000;
  p.total_range = 3000 * 100 + 1;
  const auto v = broken(p);
  EXPECT_EQ(v.parameter, "Total Measuring Range");
  EXPECT_NE(v.rule.find("integer multiple"), std::string_view::npos);
  p.total_range = 3000 * 100;
  EXPECT_FALSE(validate(p, kPhys));
}

TEST(Validate, EndlessOperationNeedsPowersOfTwo) {
  EncoderParameters p = scancon(Functionality::class2);
  p.scaling = true;
  p.measuring_units = 3000;
  p.total_range = 3000 * 64;
  EXPECT_FALSE(validate(p, kPhys));  // not endless: no restriction
  p.endless = true;
  EXPECT_EQ(broken(p).parameter, "Measuring Units per Revolution");
  EXPECT_NE(broken(p).rule.find("power of 2"), std::string_view::npos);
  p.measuring_units = 4096;
  p.total_range = 4096 * 3;
  EXPECT_EQ(broken(p).parameter, "Total Measuring Range");
  EXPECT_NE(broken(p).rule.find("power of 2"), std::string_view::npos);
  p.total_range = 4096 * 4;
  EXPECT_FALSE(validate(p, kPhys));
}

TEST(Validate, DesiredUnitsAtMostPhysicalRangeForTotalAndImpulses) {
  EncoderParameters p = scancon(Functionality::scancon22);
  p.scaling = true;
  p.units_select = UnitsSelect::per_total_range;
  p.measuring_units = (1u << 25) + 1;
  EXPECT_EQ(broken(p).parameter, "Desired Measuring Units");
  p.measuring_units = 100000;
  EXPECT_FALSE(validate(p, kPhys));
  p.units_select = UnitsSelect::per_physical_impulses;
  p.physical_impulses = 0;
  EXPECT_EQ(broken(p).parameter, "Physical Impulses");
  p.physical_impulses = (1u << 25) + 1;
  EXPECT_EQ(broken(p).parameter, "Physical Impulses");
  p.physical_impulses = 3;  // 100000 units per 3 steps: range 2^25 × 33333 — beyond 25 bits
  EXPECT_EQ(broken(p).parameter, "Total Measuring Range");
  EXPECT_NE(broken(p).rule.find("25 bits"), std::string_view::npos);
}

TEST(Validate, WithoutStatusBitsExcludesCommissioningAndLimitSwitches) {
  EncoderParameters p = scancon(Functionality::scancon30);
  p.without_status_bits = true;
  EXPECT_FALSE(validate(p, kPhys));
  p.commissioning = true;
  EXPECT_EQ(broken(p).parameter, "Commissioning Mode Enable");
  p.commissioning = false;
  p.upper_limit_enabled = true;
  EXPECT_EQ(broken(p).parameter, "Enable Lower/Upper Limit Switch");
}

TEST(Validate, LimitSwitchRanges) {
  EncoderParameters p = scancon(Functionality::scancon21);
  p.upper_limit_enabled = true;
  p.upper_limit = 0;
  EXPECT_EQ(broken(p).parameter, "Upper Limit Switch");
  p.upper_limit = 1u << 25;
  EXPECT_EQ(broken(p).parameter, "Upper Limit Switch");
  p.upper_limit = 1000;
  p.lower_limit_enabled = true;
  p.lower_limit = 1u << 25;
  EXPECT_EQ(broken(p).parameter, "Lower Limit Switch");
  p.lower_limit = 1000;
  EXPECT_EQ(broken(p).rule, "must be below the upper limit switch");
  p.lower_limit = 999;
  EXPECT_FALSE(validate(p, kPhys));
}

TEST(Validate, EncoderTypeMustMatch) {
  EncoderParameters p = scancon(Functionality::scancon21);
  p.multiturn = false;
  EXPECT_EQ(broken(p).parameter, "Encoder Type");
}

TEST(Validate, StatusBitsLimitThePositionTo25Bits) {
  const PhysicalResolution big{65536, 32768};  // 2^31 steps
  EncoderParameters p = scancon(Functionality::scancon30);
  auto v = validate(p, big);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->limit, 1u << 25);
  p.without_status_bits = true;  // 4.3.5: 31 bits without status bits
  EXPECT_FALSE(validate(p, big));
  p = scancon(Functionality::class2);  // class 2 has 31 bits
  EXPECT_FALSE(validate(p, big));
}

TEST(Validate, PhysicalResolutionLimits) {
  EXPECT_EQ(validate(scancon(), PhysicalResolution{1u << 17, 16})->parameter, "Singleturn Resolution");
  EXPECT_EQ(validate(scancon(), PhysicalResolution{8000, 16})->parameter, "Singleturn Resolution");
  EXPECT_EQ(validate(scancon(), PhysicalResolution{8192, 1u << 16})->parameter, "Number of Revolutions");
}

}  // namespace
}  // namespace cellctl::encoder

// Extended diagnosis (manual 4.2), both lengths, every field.
#include "encoder/diagnosis.hpp"

#include <gtest/gtest.h>

#include <array>
#include <variant>

#include "wire/hex.hpp"

namespace cellctl::encoder {
namespace {

std::vector<std::uint8_t> bytes(std::string_view hex) {
  return wire::parse_hex(hex).value();
}

TEST(Diagnosis, ShortFormTenOctets) {
  // header 0x0a, alarms: supply voltage, status: ccw + class 2 + scaling, multiturn, 8192 steps, 4096 revs
  const auto ext = bytes("0a 02 0b 01 00 00 20 00 10 00");
  auto r = decode_diagnosis(ext);
  ASSERT_TRUE(std::holds_alternative<EncoderDiagnosis>(r));
  const auto& d = std::get<EncoderDiagnosis>(r);
  EXPECT_EQ(d.alarms, alarm::supply_voltage);
  EXPECT_EQ(d.status, (OperatingStatus{true, true, false, true}));
  EXPECT_TRUE(d.multiturn());
  EXPECT_EQ(d.singleturn_resolution, 8192u);
  EXPECT_EQ(d.revolutions, 4096u);
  EXPECT_FALSE(d.detail);
  std::array<std::uint8_t, 64> out{};
  ASSERT_EQ(encode_diagnosis(d, out), 10u);
  EXPECT_EQ(wire::to_hex(std::span(out).first(10)), wire::to_hex(ext));
}

TEST(Diagnosis, LongFormFiftyOneOctets) {
  const auto ext = bytes(
      "33 01 02 01 00 00 20 00 10 00"  // header 51, position error, class 2, multiturn, 8192, 4096
      " 00 00 03 00 22 00 36"     // additional alarms, supported 0x0003, warnings 0x0022, supported 0x0036
      " 01 01 02 00"              // profile 1.1, software 2.0
      " 00 00 00 3d"              // operating time 61 = 6.1 h
      " ff ff ff 9c 00 00 00 00"  // offset -100, manufacturer offset 0
      " 00 00 10 00 01 00 00 00"  // 4096 units per revolution, total 16777216
      " 2a 2a 2a 2a 2a 2a 2a 2a 2a 2a");
  ASSERT_EQ(ext.size(), 51u);
  auto r = decode_diagnosis(ext);
  ASSERT_TRUE(std::holds_alternative<EncoderDiagnosis>(r));
  const auto& d = std::get<EncoderDiagnosis>(r);
  ASSERT_TRUE(d.detail);
  const auto& x = *d.detail;
  EXPECT_EQ(d.alarms, alarm::position_error);
  EXPECT_EQ(x.additional_alarms, 0);
  EXPECT_EQ(x.supported_alarms, alarm::supported);
  EXPECT_EQ(x.warnings, warning::temperature_exceeded | warning::battery_charge);
  EXPECT_EQ(x.supported_warnings, warning::supported);
  EXPECT_EQ(x.profile_version, (Version{1, 1}));
  EXPECT_EQ(x.software_version, (Version{2, 0}));
  EXPECT_EQ(x.operating_time_tenth_h, 61u);
  EXPECT_EQ(x.offset, -100);
  EXPECT_EQ(x.manufacturer_offset, 0);
  EXPECT_EQ(x.units_per_revolution, 4096u);
  EXPECT_EQ(x.total_range, 16777216u);
  EXPECT_EQ(std::string(x.serial.begin(), x.serial.end()), "**********");
  std::array<std::uint8_t, 64> out{};
  ASSERT_EQ(encode_diagnosis(d, out), 51u);
  EXPECT_EQ(wire::to_hex(std::span(out).first(51)), wire::to_hex(ext));
}

TEST(Diagnosis, TypedErrorsOnGarbage) {
  EXPECT_EQ(std::get<DiagError>(decode_diagnosis(bytes("0a 00 00 01"))), DiagError::bad_length);
  EXPECT_EQ(std::get<DiagError>(decode_diagnosis(bytes("33 00 00 01 00 00 20 00 10 00"))),
            DiagError::header_mismatch);
  EXPECT_EQ(std::get<DiagError>(decode_diagnosis(bytes("0a 20 00 01 00 00 20 00 10 00"))),
            DiagError::unassigned_bits_set);
  EXPECT_EQ(std::get<DiagError>(decode_diagnosis(bytes("0a 00 10 01 00 00 20 00 10 00"))),
            DiagError::unassigned_bits_set);
  std::array<std::uint8_t, 9> small{};
  EXPECT_EQ(encode_diagnosis(EncoderDiagnosis{}, small), 0u);
}

}  // namespace
}  // namespace cellctl::encoder

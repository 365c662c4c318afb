// Cyclic input/output (manual 4.3) and the velocity time bases.
#include "encoder/cyclic.hpp"

#include <gtest/gtest.h>

#include <array>
#include <variant>

#include "encoder/scaling.hpp"
#include "wire/hex.hpp"

namespace cellctl::encoder {
namespace {

std::vector<std::uint8_t> cyclic_bytes(std::string_view hex) {
  return wire::parse_hex(hex).value();
}

TEST(CyclicInput, Scancon22PositionStatusAndSignedVelocity) {
  // ready + mode + ccw, position 0x00123456; velocity -2
  auto r = decode_input(Functionality::scancon22, true, cyclic_bytes("16 12 34 56 ff fe"));
  ASSERT_TRUE(std::holds_alternative<CyclicInput>(r));
  const auto& in = std::get<CyclicInput>(r);
  EXPECT_EQ(in.position(true), 0x00123456u);
  EXPECT_EQ(in.velocity, -2);
  const StatusBits s = in.status();
  EXPECT_TRUE(s.ready);
  EXPECT_FALSE(s.commissioning);
  EXPECT_TRUE(s.ccw);
  EXPECT_FALSE(s.limit_switch || s.preset || s.teach_in_start || s.teach_in_end);
  std::array<std::uint8_t, 8> out{};
  ASSERT_EQ(encode_input(Functionality::scancon22, in, out), 6u);
  EXPECT_EQ(wire::to_hex(std::span(out).first(6)), "16 12 34 56 ff fe");
}

TEST(CyclicInput, Scancon30WithoutStatusBitsUses31Bits) {
  auto r = decode_input(Functionality::scancon30, false, cyclic_bytes("7f ff ff ff 80 00 7f ff"));
  const auto& in = std::get<CyclicInput>(r);
  EXPECT_EQ(in.position(false), 0x7FFFFFFFu);
  EXPECT_EQ(in.velocity, INT16_MIN);
  EXPECT_EQ(in.acceleration, INT16_MAX);
  EXPECT_TRUE(saturated(in.velocity));
  EXPECT_TRUE(saturated(in.acceleration));
  EXPECT_FALSE(saturated(-32767));
  EXPECT_EQ(std::get<CyclicError>(
                decode_input(Functionality::scancon30, false, cyclic_bytes("80 00 00 00 00 00 00 00"))),
            CyclicError::bit31_set);
}

TEST(CyclicInput, LengthsPerFunctionality) {
  EXPECT_TRUE(std::holds_alternative<CyclicInput>(
      decode_input(Functionality::class1, false, cyclic_bytes("00 00 00 01"))));
  EXPECT_EQ(
      std::get<CyclicError>(decode_input(Functionality::class2, false, cyclic_bytes("00 00 00 01 00 00"))),
      CyclicError::bad_length);
  EXPECT_EQ(
      std::get<CyclicError>(decode_input(Functionality::scancon30, true, cyclic_bytes("00 00 00 01 00 00"))),
      CyclicError::bad_length);
}

TEST(CyclicOutput, BigEndianWord) {
  std::array<std::uint8_t, 4> out{};
  ASSERT_EQ(encode_output(0x80000123u, out), 4u);
  EXPECT_EQ(wire::to_hex(out), "80 00 01 23");
  EXPECT_EQ(decode_output(out), 0x80000123u);
  EXPECT_FALSE(decode_output(cyclic_bytes("00 00 00")));
}

TEST(Velocity, SaturatesAtTheExtremes) {
  EXPECT_EQ(saturate16(40000.0), INT16_MAX);
  EXPECT_EQ(saturate16(-40000.0), INT16_MIN);
  EXPECT_EQ(saturate16(-12.4), -12);
}

TEST(Velocity, TimeBasesToUnitsPerSecond) {
  EXPECT_DOUBLE_EQ(units_per_second(500, TimeBase::steps_per_s, 4096), 500.0);
  EXPECT_DOUBLE_EQ(units_per_second(500, TimeBase::steps_per_100ms, 4096), 5000.0);
  EXPECT_DOUBLE_EQ(units_per_second(500, TimeBase::steps_per_10ms, 4096), 50000.0);
  EXPECT_DOUBLE_EQ(units_per_second(60, TimeBase::rpm, 4096), 4096.0);  // 60 rpm = 1 rev/s
  for (auto tb : {TimeBase::steps_per_s, TimeBase::steps_per_100ms, TimeBase::steps_per_10ms, TimeBase::rpm})
    EXPECT_DOUBLE_EQ(in_time_base(units_per_second(123, tb, 4096), tb, 4096), 123.0);
}

TEST(Scaling, PerRevolutionPerTotalRangeAndPerPhysicalImpulses) {
  const PhysicalResolution phys{8192, 4096};
  EncoderParameters p;
  p.functionality = Functionality::scancon21;
  EXPECT_EQ(Scaling(p, phys).to_units(12345), 12345u);  // scaling off: physical steps
  EXPECT_EQ(Scaling(p, phys).range(), 1u << 25);
  p.scaling = true;
  p.measuring_units = 1000;
  p.total_range = 1000 * 16;
  Scaling per_rev(p, phys);
  EXPECT_EQ(per_rev.to_units(8192 * 3 + 4096), 3500u);
  EXPECT_EQ(per_rev.to_units(8192 * 17), 1000u);  // rolls over at the total measuring range
  EXPECT_DOUBLE_EQ(per_rev.units_per_revolution(), 1000.0);
  p.units_select = UnitsSelect::per_total_range;
  p.measuring_units = 1'000'000;
  Scaling per_total(p, phys);
  EXPECT_EQ(per_total.range(), 1'000'000u);
  EXPECT_EQ(per_total.to_units(1u << 24), 500'000u);
  p.units_select = UnitsSelect::per_physical_impulses;
  p.measuring_units = 10;
  p.physical_impulses = 3;  // a non-integer gearing: 10 units per 3 steps
  Scaling per_impulse(p, phys);
  EXPECT_EQ(per_impulse.to_units(7), 23u);
  EXPECT_NEAR(per_impulse.units_per_revolution(), 8192.0 * 10 / 3, 1e-9);
}

}  // namespace
}  // namespace cellctl::encoder

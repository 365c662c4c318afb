// The handshakes step by step, master (Handshake) against the encoder (EncoderDevice), each row
// checked against the tables of manual 4.3.2–4.3.5 and 4.4 (bits 31…25 of output and input).
#include "encoder/handshake.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "encoder/encoder_device.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;

// One table row as the manual writes it: bits 31 … 25, 'X' = don't care.
bool matches(std::uint32_t word, std::string_view row) {
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (row[i] == 'X') continue;
    const bool set = (word >> (31 - i)) & 1u;
    if (set != (row[i] == '1')) return false;
  }
  return true;
}

struct HandshakeRig {
  explicit HandshakeRig(EncoderParameters p)
      : device(DeviceIdentity{PhysicalResolution{8192, 4096}}, NonVolatile{}) {
    device.parameterize(p);
    device.sample(1.0, link::TimePoint{});
  }
  // One Data_Exchange: the master's output, the encoder's input.
  std::pair<std::uint32_t, std::uint32_t> exchange() {
    const std::uint32_t out = hs.output();
    const CyclicInput in = device.exchange(out);
    hs.on_input(in);
    return {out, in.word};
  }
  EncoderDevice device;
  Handshake hs;
};

EncoderParameters commissioning(Functionality f = Functionality::scancon21) {
  EncoderParameters p;
  p.functionality = f;
  p.commissioning = true;  // the tables show bit 26 (Mode) clear
  return p;
}

TEST(Handshake, PresetScanconWithStatusBitsFollowsTable433) {
  HandshakeRig rig(commissioning());
  ASSERT_TRUE(rig.hs.start_preset(5000, true));
  auto [out1, in1] = rig.exchange();
  EXPECT_TRUE(matches(out1, "1000000"));
  EXPECT_EQ(out1 & bits::position25, 5000u);
  EXPECT_TRUE(matches(in1, "1000001"));  // acknowledged, new position value
  EXPECT_EQ(in1 & bits::position25, 5000u);
  auto [out2, in2] = rig.exchange();
  EXPECT_EQ(out2, 0u);  // bit 31 cleared from master
  EXPECT_TRUE(matches(in2, "0000001"));
  EXPECT_EQ(in2 & bits::position25, 5000u);
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
  EXPECT_EQ(rig.hs.result(), 5000u);
  EXPECT_EQ(rig.device.eeprom().offset, 5000 - 8192);  // the shaft stands at one revolution
}

TEST(Handshake, PresetScancon30WithoutStatusBitsFollowsTable435) {
  EncoderParameters p;
  p.functionality = Functionality::scancon30;
  p.without_status_bits = true;
  HandshakeRig rig(p);
  ASSERT_TRUE(rig.hs.start_preset(0x01234567, false));
  auto [out1, in1] = rig.exchange();
  EXPECT_EQ(out1, 0x81234567u);  // bit 31 + 31-bit value
  EXPECT_TRUE(matches(in1, "0"));
  EXPECT_EQ(in1, 0x01234567u);
  auto [out2, in2] = rig.exchange();
  EXPECT_EQ(out2, 0u);
  EXPECT_EQ(in2, 0x01234567u);
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
}

TEST(Handshake, PresetClass2FollowsTable432) {
  EncoderParameters p;
  p.functionality = Functionality::class2;
  HandshakeRig rig(p);
  ASSERT_TRUE(rig.hs.start_preset(100, false));
  auto [out1, in1] = rig.exchange();
  EXPECT_EQ(out1, 0x80000064u);
  EXPECT_EQ(in1, 100u);
  auto [out2, in2] = rig.exchange();
  EXPECT_EQ(out2, 0u);
  EXPECT_EQ(in2, 100u);
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
}

TEST(Handshake, PresetBeyondTheRangeIsNotAcknowledged) {
  EncoderParameters p = commissioning();
  p.scaling = true;
  p.measuring_units = 1000;
  p.total_range = 16000;
  HandshakeRig rig(p);
  ASSERT_TRUE(rig.hs.start_preset(16000, true));  // must be ≤ total range − 1
  for (std::uint32_t i = 0; i < Handshake::kMaxExchanges; ++i) (void)rig.exchange();
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::failed);
  EXPECT_NE(rig.hs.failure().find("preset not acknowledged"), std::string_view::npos);
  EXPECT_EQ(rig.device.eeprom().offset, 0);
}

TEST(Handshake, CountingDirectionFollowsTable441) {
  HandshakeRig rig(commissioning(Functionality::scancon22));
  ASSERT_TRUE(rig.hs.start_direction(CodeSequence::ccw));
  auto [out1, in1] = rig.exchange();
  EXPECT_TRUE(matches(out1, "0001000"));
  EXPECT_EQ(out1 & bits::position25, 1u);  // the wanted sequence in bit 0
  EXPECT_TRUE(matches(in1, "0001001"));    // acknowledge in bit 28 …
  EXPECT_EQ(in1 & bits::position25, 1u);   // … and bit 0
  auto [out2, in2] = rig.exchange();
  EXPECT_EQ(out2, 0u);
  EXPECT_TRUE(matches(in2, "0001X01"));  // new position with the new counting direction
  EXPECT_EQ(in2 & bits::position25, (1u << 25) - 8192u);
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
  EXPECT_EQ(rig.device.eeprom().code_sequence, CodeSequence::ccw);  // stored non-volatile

  ASSERT_TRUE((rig.hs.reset(), rig.hs.start_direction(CodeSequence::cw)));
  auto [out3, in3] = rig.exchange();
  EXPECT_EQ(out3, bits::code_sequence);
  EXPECT_TRUE(matches(in3, "0000001"));
  EXPECT_EQ(in3 & bits::position25, 0u);
  (void)rig.exchange();
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
  EXPECT_EQ(rig.hs.result(), 8192u);
}

TEST(Handshake, TeachInStartAndEndFollowTables442) {
  HandshakeRig rig(commissioning(Functionality::scancon30));
  ASSERT_TRUE(rig.hs.start_teach_in());
  auto [out1, in1] = rig.exchange();
  EXPECT_TRUE(matches(out1, "0100000"));
  EXPECT_TRUE(matches(in1, "010XX01"));  // slave acknowledges with bit 30
  auto [out2, in2] = rig.exchange();
  EXPECT_EQ(out2, 0u);
  EXPECT_TRUE(matches(in2, "010XX01"));  // bit 30 stays: Teach-In running, un-scaled position
  EXPECT_EQ(in2 & bits::position25, 8192u);
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
  EXPECT_TRUE(rig.device.teach_in_running());

  rig.device.sample(11.0, link::TimePoint{} + 10s);  // the operator moves 10 revolutions = 81920 steps
  rig.hs.reset();
  ASSERT_TRUE(rig.hs.end_teach_in(1000));  // … which are 1000 units
  auto [out3, in3] = rig.exchange();
  EXPECT_TRUE(matches(out3, "0010000"));
  EXPECT_EQ(out3 & bits::position25, 1000u);
  EXPECT_TRUE(matches(in3, "011XX01"));
  const std::uint32_t total = 409600;  // 1000 units × 2^25 / 81920 steps
  EXPECT_EQ(in3 & bits::position25, total);
  auto [out4, in4] = rig.exchange();
  EXPECT_EQ(out4, 0u);
  EXPECT_TRUE(matches(in4, "000XX01"));
  EXPECT_EQ(in4 & bits::position25, 1100u);  // scaled with the new factor: 11 rev × 100 units
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::done);
  EXPECT_EQ(rig.hs.result(), total);
  EXPECT_EQ(rig.device.eeprom().taught_units, total);
  EXPECT_EQ(rig.device.diagnosis().detail->total_range, total);
}

TEST(Handshake, TeachInNeedsCommissioningMode) {
  EncoderParameters p;
  p.functionality = Functionality::scancon21;
  HandshakeRig rig(p);
  ASSERT_TRUE(rig.hs.start_teach_in());
  for (std::uint32_t i = 0; i < Handshake::kMaxExchanges; ++i) {
    auto [out, in] = rig.exchange();
    EXPECT_TRUE(matches(in, "0000011"));  // Mode set: not commissioning, request ignored
  }
  EXPECT_EQ(rig.hs.phase(), Handshake::Phase::failed);
  EXPECT_NE(rig.hs.failure().find("Teach-In start not acknowledged"), std::string_view::npos);
}

TEST(Handshake, OneAtATimeAndValueLimits) {
  Handshake hs;
  EXPECT_FALSE(hs.start_preset(1u << 25, true));
  EXPECT_FALSE(hs.end_teach_in(0));
  ASSERT_TRUE(hs.start_preset(1, true));
  EXPECT_FALSE(hs.start_direction(CodeSequence::ccw));
  EXPECT_EQ(hs.kind(), Handshake::Kind::preset);
}

TEST(EncoderDevice, VelocityAndAccelerationOverTheTimeBaseWithSaturation) {
  EncoderParameters p;
  p.functionality = Functionality::scancon30;
  p.time_base = TimeBase::steps_per_100ms;
  EncoderDevice dev(DeviceIdentity{PhysicalResolution{8192, 4096}}, NonVolatile{});
  dev.parameterize(p);
  link::TimePoint t{};
  dev.sample(0.0, t);
  dev.sample(0.25, t += 100ms);  // 2048 steps in 100 ms
  auto in = dev.exchange(0u);
  EXPECT_EQ(in.velocity, 2048);
  EXPECT_EQ(in.acceleration, 2048);
  dev.sample(0.5, t += 100ms);
  in = dev.exchange(0u);
  EXPECT_EQ(in.velocity, 2048);
  EXPECT_EQ(in.acceleration, 0);
  dev.sample(10.5, t += 100ms);  // 81920 steps: beyond 16 bits
  in = dev.exchange(0u);
  EXPECT_EQ(in.velocity, INT16_MAX);
  EXPECT_EQ(in.acceleration, INT16_MAX);
  dev.sample(0.5, t += 100ms);
  in = dev.exchange(0u);
  EXPECT_EQ(in.velocity, INT16_MIN);
  EXPECT_EQ(in.acceleration, INT16_MIN);
}

TEST(EncoderDevice, LimitSwitchesAndDiagnosisLengths) {
  EncoderParameters p;
  p.functionality = Functionality::scancon21;
  p.lower_limit_enabled = p.upper_limit_enabled = true;
  p.lower_limit = 1000;
  p.upper_limit = 20000;
  EncoderDevice dev(DeviceIdentity{PhysicalResolution{8192, 4096}}, NonVolatile{});
  dev.parameterize(p);
  dev.sample(0.1, link::TimePoint{});
  EXPECT_TRUE(dev.exchange(0u).status().limit_switch);  // 819 < 1000
  dev.sample(1.0, link::TimePoint{});
  EXPECT_FALSE(dev.exchange(0u).status().limit_switch);
  dev.sample(3.0, link::TimePoint{});
  EXPECT_TRUE(dev.exchange(0u).status().limit_switch);  // 24576 > 20000
  EXPECT_EQ(dev.diagnosis().length(), 51u);
  p.short_diagnosis = true;
  dev.parameterize(p);
  EXPECT_EQ(dev.diagnosis().length(), 10u);
  p.functionality = Functionality::class1;
  dev.parameterize(p);
  EXPECT_EQ(dev.diagnosis().length(), 10u);
  dev.set_alarm(alarm::position_error | alarm::memory_error, true);  // memory error is not supported
  EXPECT_EQ(dev.alarms(), alarm::position_error);
  dev.set_warning(warning::battery_charge | warning::reference_point, true);
  EXPECT_EQ(dev.warnings(), warning::battery_charge);
}

}  // namespace
}  // namespace cellctl::encoder

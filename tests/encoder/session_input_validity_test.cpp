// An input that is not a position is never shown as one: a Class 2 input with bit 31 set (the
// manual says it is always 0) from a third-party slave, and the Ready bit cleared by an encoder
// alarm, make the snapshot invalid, count as bad exchanges and let the input age run on. Diagnoses
// without an extended part are counted as read, with what they had.
#include <gtest/gtest.h>

#include "encoder/cyclic.hpp"
#include "profibus/dp_slave.hpp"
#include "session_rig.hpp"
#include "virtual_line.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;
using testing::Rig;

// A third-party Class 2 encoder: takes any parameters and configuration, sends `word`.
struct ThirdPartyClass2 final : profibus::SlaveBehaviour {
  std::uint32_t word = 1000;
  profibus::PrmVerdict check_prm(std::span<const std::uint8_t>) override { return {}; }
  bool check_cfg(std::span<const std::uint8_t>) override { return true; }
  std::size_t ext_diag(std::span<std::uint8_t>) override { return 0; }
  std::size_t exchange(std::span<const std::uint8_t>, std::span<std::uint8_t> inputs) override {
    return encode_output(word, inputs);  // 4 octets, big-endian: the same shape as the input word
  }
};

TEST(EncoderInput, Class2InputWithBit31SetIsInvalidAndCountedNeverAFreshPosition) {
  link::VirtualClock clock;
  link::SimLink sim(clock, link::line_8e1(1'500'000));
  ThirdPartyClass2 device;
  profibus::DpSlave slave(sim.device(), profibus::DpSlaveConfig{.address = 5, .ident = kIdentNumber}, device);
  SessionConfig config;
  config.station_address = 5;
  config.parameters.functionality = Functionality::class2;
  config.counts_per_mm = 100.0;
  config.bus.master_address = 2;
  Session session(sim.master(), config);
  session.activate(clock.now());
  const auto run_for = [&](link::Duration d) {
    (void)testing::run_line_until(
        clock, sim, [] { return false; }, d, session, slave);
  };
  run_for(20ms);
  const Snapshot& s = session.snapshot();
  ASSERT_TRUE(s.data_exchange) << session.fault_reason();
  EXPECT_TRUE(s.input_valid);
  EXPECT_DOUBLE_EQ(s.position_mm, 10.0);
  EXPECT_EQ(s.bad_inputs, 0u);
  EXPECT_LT(s.input_age, 2ms);

  device.word = 0x8000'0000u | 2000u;  // bit 31 set: not a Class 2 position
  run_for(10ms);
  EXPECT_FALSE(s.input_valid);
  EXPECT_EQ(s.input_fault, "bit 31 set in a position without status bits");
  EXPECT_DOUBLE_EQ(s.position_mm, 10.0) << "the last valid position stays, marked invalid";
  EXPECT_GE(s.bad_inputs, 5u);
  EXPECT_GE(s.input_age, 9ms) << "the age runs on from the last valid input";

  device.word = 3000u;
  run_for(5ms);
  EXPECT_TRUE(s.input_valid);
  EXPECT_TRUE(s.input_fault.empty());
  EXPECT_DOUBLE_EQ(s.position_mm, 30.0);
  EXPECT_LT(s.input_age, 2ms);

  // Its diagnoses carry no extended part: read, and said so — not "not read yet".
  EXPECT_GE(s.diagnosis_reads, 2u);
  EXPECT_EQ(s.extended_diag_octets, 0u);
  EXPECT_TRUE(s.diagnosis_error.empty());
  EXPECT_FALSE(s.diagnosis);
}

TEST(EncoderInput, ReadyClearedByAnAlarmMakesTheInputInvalid) {
  Rig rig;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  EXPECT_TRUE(s.snapshot().input_valid);
  rig.emulator->set_alarm(alarm::position_error, true);
  rig.run_for(10ms);
  EXPECT_FALSE(s.snapshot().input_valid);
  EXPECT_EQ(s.snapshot().input_fault, "the encoder clears its Ready bit");
  EXPECT_GE(s.snapshot().bad_inputs, 5u);
  EXPECT_GE(s.snapshot().input_age, 9ms);
  rig.emulator->set_alarm(alarm::position_error, false);
  rig.run_for(5ms);
  EXPECT_TRUE(s.snapshot().input_valid);
  EXPECT_LT(s.snapshot().input_age, 2ms);
}

}  // namespace
}  // namespace cellctl::encoder

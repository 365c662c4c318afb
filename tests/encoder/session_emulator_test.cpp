// encoder::Session (DP master) against encoder::Emulator (DP slave) over SimLink at 1.5 Mbaud 8E1 in
// virtual time: start-up, refusals with the rule broken, watchdog, lost slave, the handshakes.
#include <gtest/gtest.h>

#include <filesystem>

#include "session_rig.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;
using testing::Rig;

TEST(EncoderSession, PowerOnToDataExchangeWithPositionInMm) {
  Rig rig;
  rig.move_to(10.0);  // 2.5 revolutions = 20480 steps
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  const Snapshot& snap = s.snapshot();
  EXPECT_EQ(s.lifecycle(), Lifecycle::active);
  EXPECT_EQ(snap.position_counts, 20480u);
  EXPECT_DOUBLE_EQ(snap.position_mm, 10.0);
  EXPECT_TRUE(snap.has_status_bits);
  EXPECT_TRUE(snap.status.ready);
  EXPECT_FALSE(snap.status.commissioning);
  ASSERT_TRUE(snap.diagnosis);
  EXPECT_EQ(snap.diagnosis->singleturn_resolution, 8192u);
  EXPECT_EQ(snap.diagnosis->revolutions, 4096u);
  ASSERT_TRUE(snap.diagnosis->detail);  // 57-octet diagnosis
  EXPECT_EQ(snap.diagnosis->detail->supported_warnings, warning::supported);
  EXPECT_EQ(rig.emulator->slave().state(), profibus::DpSlaveState::data_exchange);
}

TEST(EncoderSession, VelocityInMmPerSecondOverTheTimeBase) {
  Rig rig(Functionality::scancon30);
  rig.session_config.parameters.time_base = TimeBase::steps_per_10ms;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  rig.moving_since = rig.clock.now();
  rig.axis_speed_mm_s = 20.0;  // 5 rev/s = 40960 steps/s = 409.6 per 10 ms
  rig.run_for(100ms);
  EXPECT_NEAR(s.snapshot().velocity_mm_s, 20.0, 0.1);
  EXPECT_NEAR(s.snapshot().velocity_raw, 410, 1);
  EXPECT_FALSE(s.snapshot().velocity_saturated);
  EXPECT_NEAR(s.snapshot().position_mm, rig.axis_mm(), 0.1);
}

TEST(EncoderSession, BadParametersAreRefusedLocallyWithTheRule) {
  Rig rig;
  rig.session_config.parameters.scaling = true;
  rig.session_config.parameters.measuring_units = 3000;
  rig.session_config.parameters.total_range = 3000 * 10 + 7;
  Session& s = rig.start();
  s.receive(rig.clock.now());
  EXPECT_EQ(s.lifecycle(), Lifecycle::fault);
  ASSERT_TRUE(s.snapshot().local_prm_violation);
  EXPECT_EQ(s.snapshot().local_prm_violation->parameter, "Total Measuring Range");
  EXPECT_NE(s.fault_reason().find("integer multiple"), std::string::npos) << s.fault_reason();
  rig.run_for(20ms);
  EXPECT_EQ(rig.emulator->slave().counters().requests, 0u);  // nothing was sent
}

TEST(EncoderSession, SlavePrmFaultIsReportedWithTheEmulatorsRule) {
  Rig rig;
  // The master believes in a 16-bit singleturn: 16384 units per revolution pass its check …
  rig.session_config.physical = PhysicalResolution{65536, 512};
  rig.session_config.parameters.scaling = true;
  rig.session_config.parameters.measuring_units = 16384;
  rig.session_config.parameters.total_range = 16384 * 64;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return s.lifecycle() == Lifecycle::fault; }, 200ms));
  EXPECT_EQ(s.snapshot().startup_fault, profibus::StartupFault::Kind::prm_fault);
  EXPECT_TRUE(s.snapshot().standard_diag.prm_fault);
  EXPECT_NE(s.fault_reason().find("Prm_Fault"), std::string::npos) << s.fault_reason();
  EXPECT_NE(s.fault_reason().find("the encoder reports 8192 × 4096"), std::string::npos) << s.fault_reason();
  // … the emulated encoder with 8192 steps refuses it, naming the rule.
  EXPECT_NE(rig.emulator->last_prm_reason().find("Desired Measuring Units: must be 1 … the physical steps"),
            std::string_view::npos)
      << rig.emulator->last_prm_reason();
  EXPECT_NE(rig.emulator->slave().state(), profibus::DpSlaveState::data_exchange);
  rig.run_for(50ms);
  EXPECT_EQ(rig.emulator->slave().counters().data_exchanges, 0u);
}

TEST(EncoderSession, ParametersTheChosenConfigurationDoesNotAllowGiveCfgFault) {
  Rig rig(Functionality::scancon22);
  rig.session_config.parameters.without_status_bits = true;  // a Scancon 3.0 parameter
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return s.lifecycle() == Lifecycle::fault; }, 200ms));
  EXPECT_EQ(s.snapshot().startup_fault, profibus::StartupFault::Kind::cfg_fault);
  EXPECT_NE(s.fault_reason().find("Cfg_Fault"), std::string::npos) << s.fault_reason();
  EXPECT_EQ(rig.emulator->last_cfg_reason(),
            "parameters not allowed with scancon2.2: Without Status Bits: only with the Scancon 3.0 "
            "functionality (4.1.5 bit 4)");
  EXPECT_EQ(rig.emulator->slave().counters().data_exchanges, 0u);
}

TEST(EncoderSession, TheEmulatorTakesTheFunctionalityTheMasterChooses) {
  // One emulator, started up by masters of each functionality in turn (re-parameterisation).
  Rig rig;
  rig.move_to(10.0);
  for (const Functionality f : kFunctionalities) {
    rig.session_config.parameters.functionality = f;
    Session& s = rig.start();
    ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 300ms)) << to_string(f) << s.fault_reason();
    EXPECT_EQ(rig.emulator->device().parameters().functionality, f);
    EXPECT_TRUE(s.snapshot().input_valid) << to_string(f);
    EXPECT_DOUBLE_EQ(s.snapshot().position_mm, 10.0) << to_string(f);
    EXPECT_TRUE(rig.emulator->last_prm_reason().empty());
    EXPECT_TRUE(rig.emulator->last_cfg_reason().empty());
  }
}

TEST(EncoderSession, SilentMasterLetsTheEncoderWatchdogFire) {
  Rig rig;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  EXPECT_EQ(rig.emulator->watchdog_expiries(), 0u);
  // The master stops; 100 ms watchdog (10 ms × 2 × 5).
  EXPECT_FALSE(rig.run_until([&] { return rig.emulator->watchdog_expiries() > 0; }, 95ms, false));
  EXPECT_TRUE(rig.run_until([&] { return rig.emulator->watchdog_expiries() > 0; }, 20ms, false));
  EXPECT_NE(rig.emulator->slave().state(), profibus::DpSlaveState::data_exchange);
}

TEST(EncoderSession, SilentSlaveIsDetectedInTimeAndRecovers) {
  Rig rig;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  rig.emulator->set_silent(true);
  const auto silent_at = rig.clock.now();
  ASSERT_TRUE(rig.run_until([&] { return !s.snapshot().data_exchange; }, 200ms));
  EXPECT_LE(rig.clock.now() - silent_at, 50ms + 5ms);  // lost_slave_time + one request's slot time
  EXPECT_GE(s.snapshot().input_age, 45ms);
  rig.emulator->set_silent(false);
  const auto before = s.snapshot().exchanges;
  ASSERT_TRUE(rig.run_until([&] { return s.snapshot().data_exchange && s.snapshot().exchanges > before + 2; },
                            500ms));
  EXPECT_EQ(s.lifecycle(), Lifecycle::active);
}

TEST(EncoderSession, PresetThroughTheMaster) {
  Rig rig;
  rig.move_to(6.0);
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  EXPECT_FALSE(s.preset(1u << 25));  // beyond the total range
  ASSERT_TRUE(s.preset(1000));
  EXPECT_FALSE(s.preset(1));  // one at a time
  ASSERT_TRUE(rig.run_until([&] { return s.snapshot().command.phase >= Handshake::Phase::done; }, 100ms));
  EXPECT_EQ(s.snapshot().command.phase, Handshake::Phase::done) << s.snapshot().command.failure;
  EXPECT_EQ(s.snapshot().command.result, 1000u);
  rig.run_for(5ms);
  EXPECT_EQ(s.snapshot().position_counts, 1000u);
  EXPECT_FALSE(s.snapshot().status.preset);
  EXPECT_EQ(rig.emulator->device().eeprom().offset, 1000 - 12288);
}

TEST(EncoderSession, DirectionAndTeachInNeedCommissioningMode) {
  Rig rig;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms));
  EXPECT_FALSE(s.set_direction(CodeSequence::ccw));
  EXPECT_FALSE(s.teach_in_start());
}

TEST(EncoderSession, DirectionChangeThroughTheMaster) {
  Rig rig;
  rig.session_config.parameters.commissioning = true;
  rig.move_to(4.0);  // one revolution
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  EXPECT_TRUE(s.snapshot().status.commissioning);
  ASSERT_TRUE(s.set_direction(CodeSequence::ccw));
  ASSERT_TRUE(rig.run_until([&] { return s.snapshot().command.phase >= Handshake::Phase::done; }, 100ms));
  EXPECT_EQ(s.snapshot().command.phase, Handshake::Phase::done) << s.snapshot().command.failure;
  rig.run_for(5ms);
  EXPECT_TRUE(s.snapshot().status.ccw);
  EXPECT_EQ(s.snapshot().position_counts, (1u << 25) - 8192u);
  EXPECT_EQ(rig.emulator->device().eeprom().code_sequence, CodeSequence::ccw);
}

TEST(EncoderSession, TeachInThroughTheMaster) {
  Rig rig(Functionality::scancon30);
  rig.session_config.parameters.commissioning = true;
  rig.session_config.parameters.scaling = true;
  rig.session_config.parameters.units_select = UnitsSelect::per_total_range;
  rig.session_config.parameters.measuring_units = 1u << 25;
  rig.move_to(4.0);
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  const auto finished = [&] { return s.snapshot().command.phase >= Handshake::Phase::done; };
  ASSERT_TRUE(s.teach_in_start());
  ASSERT_TRUE(rig.run_until(finished, 100ms));
  ASSERT_EQ(s.snapshot().command.phase, Handshake::Phase::done) << s.snapshot().command.failure;
  EXPECT_TRUE(s.snapshot().status.teach_in_start);
  s.clear_command();
  rig.move_to(44.0);  // ten revolutions further
  rig.run_for(5ms);
  EXPECT_EQ(s.snapshot().position_counts, 11u * 8192u);  // un-scaled during Teach-In
  ASSERT_TRUE(s.teach_in_end(1000));
  ASSERT_TRUE(rig.run_until(finished, 100ms));
  ASSERT_EQ(s.snapshot().command.phase, Handshake::Phase::done) << s.snapshot().command.failure;
  EXPECT_EQ(s.snapshot().command.result, 409600u);  // 1000 units × 2^25 / 81920 steps
  rig.run_for(5ms);
  EXPECT_FALSE(s.snapshot().status.teach_in_start);
  EXPECT_EQ(s.snapshot().position_counts, 1100u);
}

TEST(EncoderSession, InjectedAlarmRaisesADiagnosis) {
  Rig rig;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms));
  const auto reads = s.snapshot().diagnosis_reads;
  rig.emulator->set_alarm(alarm::position_error, true);
  rig.emulator->set_warning(warning::temperature_exceeded | warning::battery_charge, true);
  ASSERT_TRUE(rig.run_until([&] { return s.snapshot().diagnosis_reads > reads; }, 20ms));
  rig.run_for(3ms);
  ASSERT_TRUE(s.snapshot().diagnosis && s.snapshot().diagnosis->detail);
  EXPECT_EQ(s.snapshot().diagnosis->alarms, alarm::position_error);
  EXPECT_EQ(s.snapshot().diagnosis->detail->warnings,
            warning::temperature_exceeded | warning::battery_charge);
  EXPECT_FALSE(s.snapshot().status.ready);
  EXPECT_TRUE(s.snapshot().data_exchange);
}

TEST(EncoderSession, AddressSetOverTheBusAndKeptInTheStateFile) {
  const auto file =
      std::filesystem::temp_directory_path() / ("cellctl-encoder-" + std::to_string(::getpid()));
  std::filesystem::remove(file);
  {
    Rig rig(Functionality::scancon22, 126, file);
    Session& s = rig.start();
    rig.run_for(5ms);
    ASSERT_TRUE(s.set_slave_address(17));
    ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 300ms)) << s.fault_reason();
    EXPECT_EQ(rig.emulator->slave().address(), 17);
    EXPECT_EQ(s.address_change_status(), profibus::RequestStatus::done);
    ASSERT_TRUE(s.preset(777));
    ASSERT_TRUE(rig.run_until([&] { return s.snapshot().command.phase == Handshake::Phase::done; }, 100ms));
  }
  Rig again(Functionality::scancon22, 126, file);  // power cycle: switches still at 126
  EXPECT_EQ(again.emulator->slave().address(), 17);
  again.session_config.station_address = 17;
  Session& s = again.start();
  ASSERT_TRUE(again.run_until([&] { return again.exchanging(); }, 200ms)) << s.fault_reason();
  EXPECT_EQ(s.snapshot().position_counts, 777u);  // the preset offset survived
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace cellctl::encoder

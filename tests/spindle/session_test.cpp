// spindle::Session against spindle::Emulator over SimLink in virtual time: start to speed, stop to rest,
// a start the converter refuses, corrupted and lost replies, silence, faults, warnings and reset.

#include "spindle/session.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "session_rig.hpp"
#include "spindle/fault_numbers.hpp"

namespace cellctl::spindle {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;

TEST(SpindleSession, ActivationReadsIdentificationStatusAndValues) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate()) << rig.session.fault_reason();
  const auto& s = rig.session.snapshot();
  ASSERT_TRUE(s.identification.has_value());
  EXPECT_EQ(s.identification->converter_type, 4625);
  EXPECT_EQ(s.identification->firmware, 0x0433);
  EXPECT_EQ(s.identification->serial_number, 20240117u);
  EXPECT_TRUE(s.at_rest);
  EXPECT_FALSE(s.at_speed);
  EXPECT_EQ(s.state, DeviceState::none);
  EXPECT_EQ(s.converter_hours, 269u);
  EXPECT_EQ(s.motor_hours, 6u);
  EXPECT_DOUBLE_EQ(s.peak_current_a, 8.0);
  EXPECT_EQ(rig.session.health().bad_frames, 0u);
}

TEST(SpindleSession, StartAt400HzReachesSpeedAndReportsIt) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  const auto t0 = rig.clock.now();
  ASSERT_TRUE(rig.session.start(400.0, Direction::counter_clockwise));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }))
      << rig.session.fault_reason();
  // 400 Hz at 400 Hz/s is 1 s of ramp, plus three telegrams and one poll period.
  const double took = link::to_seconds(rig.clock.now() - t0);
  EXPECT_GT(took, 1.0);
  EXPECT_LT(took, 1.1);
  EXPECT_EQ(rig.emulator.start_parameters(),
            (SetStart{Source::sycodrive, Source::sycodrive, Direction::counter_clockwise}));
  EXPECT_DOUBLE_EQ(rig.emulator.motor().frequency_hz(), -400.0);

  rig.run_for(300ms);  // one values poll later
  const auto& s = rig.session.snapshot();
  EXPECT_FALSE(s.at_rest);
  EXPECT_DOUBLE_EQ(s.set_frequency_hz, 400.0);
  EXPECT_DOUBLE_EQ(s.actual_frequency_hz, 400.0);
  EXPECT_DOUBLE_EQ(s.requested_frequency_hz, 400.0);
  EXPECT_DOUBLE_EQ(s.motor_voltage_v, 20.0);
  EXPECT_GT(s.motor_current_a, 0.5);
  EXPECT_GT(s.power_w, 5.0);
  EXPECT_EQ(s.state, DeviceState::none);
  EXPECT_EQ(rig.state, Lifecycle::active);
}

TEST(SpindleSession, StopReachesRest) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
  ASSERT_TRUE(rig.session.stop());
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.snapshot().at_rest; }));
  EXPECT_FALSE(rig.session.snapshot().at_speed);
  EXPECT_TRUE(rig.emulator.motor().at_rest());
  EXPECT_FALSE(rig.session.commands_pending());
}

TEST(SpindleSession, StopGoesBeforeEverythingQueued) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.session.stop());  // before any of the start's telegrams left
  rig.run_for(500ms);
  EXPECT_TRUE(rig.emulator.motor().at_rest());
  EXPECT_DOUBLE_EQ(rig.emulator.motor().target_hz(), 0.0);
  EXPECT_FALSE(rig.session.commands_pending());
}

TEST(SpindleSession, DeactivateStopsTheSpindleThenGoesInactive) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
  rig.session.deactivate(rig.clock.now());
  // 400 Hz run down at 800 Hz/s: 0.5 s. Inactive only once a statusout after the stop's ACK reports
  // STILLSTAND — the converter has no watchdog, so the session must not let go of a turning spindle.
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.state == Lifecycle::inactive; }));
  EXPECT_DOUBLE_EQ(rig.emulator.motor().target_hz(), 0.0);
  EXPECT_TRUE(rig.emulator.motor().at_rest()) << rig.emulator.motor().frequency_hz() << " Hz";
}

TEST(SpindleSession, StartWithoutStartParametersIsRefusedWithAReason) {
  SessionConfig config;
  config.set_start_parameters = false;  // the emulator keeps its factory P140/P141 = digital input
  SessionRig rig(config);
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(500ms, [&] { return rig.session.snapshot().start_refused; }));
  const auto& s = rig.session.snapshot();
  EXPECT_TRUE(s.at_rest);
  EXPECT_TRUE(s.warning());
  EXPECT_EQ(s.error_number, kWarningStartSourceNotRs232);
  EXPECT_NE(s.start_refused_reason.find("warning 140"), std::string::npos) << s.start_refused_reason;
  EXPECT_NE(s.start_refused_reason.find("P140/P141"), std::string::npos) << s.start_refused_reason;
  rig.run_for(1s);
  EXPECT_TRUE(rig.emulator.motor().at_rest());
  EXPECT_FALSE(rig.session.snapshot().at_speed);
  EXPECT_EQ(rig.state, Lifecycle::active);  // a refused start is the device's answer, not a link fault
}

TEST(SpindleSession, ACorruptedReplyIsRetried) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  rig.emulator.corrupt_next_checksum();  // the ACK of SET Startparameter
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }))
      << rig.session.fault_reason();
  EXPECT_EQ(rig.session.health().bad_frames, 1u);
  EXPECT_EQ(rig.session.health().retries, 1u);
  EXPECT_EQ(rig.state, Lifecycle::active);
}

TEST(SpindleSession, ALostReplyIsRetried) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  rig.emulator.drop_next_replies(2);
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }))
      << rig.session.fault_reason();
  EXPECT_EQ(rig.session.health().timeouts, 2u);
  EXPECT_EQ(rig.session.health().retries, 2u);
}

TEST(SpindleSession, SilenceBecomesALinkFault) {
  SessionConfig config;
  config.link_fault_after = 500ms;
  SessionRig rig(config);
  ASSERT_TRUE(rig.activate());
  rig.emulator.set_silent(true);
  const auto t0 = rig.clock.now();
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.state == Lifecycle::fault; }));
  EXPECT_LE(rig.clock.now() - t0, 520ms);
  EXPECT_NE(rig.session.fault_reason().find("silent"), std::string::npos) << rig.session.fault_reason();
  EXPECT_NE(rig.session.fault_reason().find("sim:spindle"), std::string::npos);
  EXPECT_GE(rig.session.health().timeouts, 3u);
}

TEST(SpindleSession, AnUnacknowledgedCommandIsAFault) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  rig.emulator.set_silent(true);
  rig.run_for(150ms);  // let any poll in flight finish or time out
  ASSERT_TRUE(rig.session.stop());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.state == Lifecycle::fault; }));
  EXPECT_NE(rig.session.fault_reason().find("did not acknowledge CMD System Stopp (0xA1) after 3 tries"),
            std::string::npos)
      << rig.session.fault_reason();
}

TEST(SpindleSession, OverTemperatureReachesTheSnapshotAndResetClearsItOnceCool) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
  rig.emulator.set_over_temperature(true);
  ASSERT_TRUE(rig.run_until(100ms, [&] { return rig.session.snapshot().fault(); }));
  EXPECT_TRUE(rig.session.snapshot().motor_over_temperature);
  EXPECT_EQ(rig.session.snapshot().error_number, kFaultMotorOverTemperature);
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.snapshot().at_rest; }));  // the converter stops it

  ASSERT_TRUE(rig.session.reset());  // still hot: the fault stays
  rig.run_for(200ms);
  EXPECT_TRUE(rig.session.snapshot().fault());

  rig.emulator.set_over_temperature(false);
  ASSERT_TRUE(rig.session.reset());
  ASSERT_TRUE(rig.run_until(200ms, [&] { return rig.session.snapshot().state == DeviceState::none; }));
  EXPECT_FALSE(rig.session.snapshot().motor_over_temperature);
  EXPECT_EQ(rig.session.snapshot().error_number, 0);
  // …and the spindle starts again.
  ASSERT_TRUE(rig.session.start(300.0));
  EXPECT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
}

TEST(SpindleSession, AnInjectedFaultReachesTheSnapshotAndResetClearsIt) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  rig.emulator.inject_fault(77);
  ASSERT_TRUE(rig.run_until(100ms, [&] { return rig.session.snapshot().fault(); }));
  EXPECT_EQ(rig.session.snapshot().error_number, 77);
  ASSERT_TRUE(rig.session.reset());
  ASSERT_TRUE(rig.run_until(200ms, [&] { return !rig.session.snapshot().fault(); }));
  EXPECT_EQ(rig.emulator.identification().fault_history[0], 77);
}

TEST(SpindleSession, CurrentLimitIsAWarningWhileTheSpindleRuns) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
  rig.emulator.set_current_limit(true);
  ASSERT_TRUE(rig.run_until(400ms, [&] {
    const auto& s = rig.session.snapshot();
    return s.current_limit && s.motor_current_a == 8.0;
  }));
  EXPECT_TRUE(rig.session.snapshot().warning());
  EXPECT_EQ(rig.session.snapshot().error_number, kWarningCurrentLimit);
  EXPECT_TRUE(rig.session.snapshot().at_speed);
  rig.emulator.set_current_limit(false);
  EXPECT_TRUE(rig.run_until(100ms, [&] { return rig.session.snapshot().state == DeviceState::none; }));
}

TEST(SpindleSession, ASetPointAboveTheMotorsMaximumFaultsTheConverter) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(1500.0));  // the test motor allows 100..1000 Hz
  ASSERT_TRUE(rig.run_until(500ms, [&] { return rig.session.snapshot().start_refused; }));
  EXPECT_TRUE(rig.session.snapshot().fault());
  EXPECT_EQ(rig.session.snapshot().error_number, kFaultSetpointOutOfRange);
  EXPECT_NE(rig.session.snapshot().start_refused_reason.find("fault 51"), std::string::npos);
  EXPECT_TRUE(rig.emulator.motor().at_rest());
}

TEST(SpindleSession, ChangingFrequencyWhileRunning) {
  SessionRig rig;
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.start(400.0));
  ASSERT_TRUE(rig.run_until(3s, [&] { return rig.session.snapshot().at_speed; }));
  ASSERT_TRUE(rig.session.set_frequency(600.0));
  ASSERT_TRUE(rig.run_until(100ms, [&] { return !rig.session.snapshot().at_speed; }));
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().at_speed; }));
  EXPECT_DOUBLE_EQ(rig.emulator.motor().frequency_hz(), 600.0);
}

TEST(SpindleSession, CommandsAreRefusedWhenNotActiveOrOutOfRange) {
  SessionRig rig;
  EXPECT_FALSE(rig.session.start(400.0));
  EXPECT_FALSE(rig.session.stop());
  ASSERT_TRUE(rig.activate());
  EXPECT_FALSE(rig.session.start(-1.0));
  EXPECT_FALSE(rig.session.start(70000.0));
  EXPECT_FALSE(rig.session.set_frequency(std::nan("")));
  EXPECT_FALSE(rig.session.start(400.0, Direction::digital_input));
}

}  // namespace
}  // namespace cellctl::spindle

// scu::Session against scu::Emulator over a SimLink at 38400 baud, in virtual time.

#include "scu/session.hpp"

#include <gtest/gtest.h>

#include "scu_rig.hpp"

namespace cellctl::scu {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;
using testing::Rig;

TEST(ScuSession, HoldsRemoteModeForTenVirtualMinutesWithoutAWatchdogLapse) {
  Rig rig(2);
  ASSERT_TRUE(rig.activate());
  const auto start_refreshes = rig.session.snapshot().refreshes;
  bool always_active = true;
  cellctl::testing::run_for(rig.clock, 1ms, 10min, [&](link::TimePoint t) {
    rig.step(t);
    always_active = always_active && rig.session.lifecycle() == Lifecycle::active;
  });
  EXPECT_TRUE(always_active);
  EXPECT_FALSE(rig.emulator.error_word().remote_timeout()) << "bit 22 must never be set";
  EXPECT_FALSE(rig.session.snapshot().watchdog_lapse_seen);
  EXPECT_TRUE(rig.emulator.remote_open());
  // RC every 100 ms: the largest gap the SCU saw stays far inside its 500 ms watchdog.
  EXPECT_LE(rig.emulator.max_cyclic_gap(), 110ms);
  EXPECT_GE(rig.emulator.max_cyclic_gap(), 100ms);
  const auto refreshes = rig.session.snapshot().refreshes - start_refreshes;
  EXPECT_NEAR(static_cast<double>(refreshes), 6000.0, 10.0);
  EXPECT_EQ(rig.session.health().timeouts, 0u);
  EXPECT_EQ(rig.session.health().bad_frames, 0u);
}

TEST(ScuSession, MoveToARemotePositionCompletesAndIsFollowedByRs) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget target[] = {{1, 50.0}};
  ASSERT_TRUE(rig.session.move_to(1, target, 10.0, true));
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::queued);
  bool saw_motion = false;
  ASSERT_TRUE(rig.run_until(20s, [&] {
    saw_motion = saw_motion || rig.session.snapshot().actuators[0].status.motion_active;
    const auto& f = rig.session.snapshot().functions[0];
    return f.outcome == MoveOutcome::arrived && !f.execution_open;
  }));
  EXPECT_TRUE(saw_motion) << "status 1 bit 4 followed the plant";
  EXPECT_FALSE(rig.emulator.execution_open(1)) << "the SCU got the RS that closes the RE";
  EXPECT_NEAR(rig.emulator.position_edges(1), 5000, 1);
  EXPECT_NEAR(rig.session.snapshot().actuators[0].position_edges, 5000, 1);
  EXPECT_FALSE(rig.session.snapshot().actuators[0].status.motion_active);
  // 50 mm at 50 % of 20 mm/s with 40 mm/s² ramps: 5.25 s of motion at least.
  EXPECT_GE(rig.clock.now().time_since_epoch(), 5s);
}

TEST(ScuSession, AStopIssuedMidMoveGoesAheadOfQueuedTelegrams) {
  Rig rig(2);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget far1[] = {{1, 150.0}};
  ASSERT_TRUE(rig.session.move_to(1, far1, 20.0, true));
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.snapshot().actuators[0].status.motion_active; }));
  // F2's three telegrams are queued first, then the stop of F1: the RS must overtake them.
  const ActuatorTarget far2[] = {{2, 150.0}};
  ASSERT_TRUE(rig.session.move_to(2, far2, 20.0, true));
  ASSERT_TRUE(rig.session.stop(1, false));
  ASSERT_TRUE(rig.run_until(1s, [&] { return !rig.emulator.execution_open(1); }));
  EXPECT_FALSE(rig.emulator.execution_open(2)) << "F2's RE was still queued behind the RS";
  EXPECT_FALSE(rig.emulator.actuator(1).active()) << "fast stop";
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.emulator.execution_open(2); }));
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::stopped_short);
}

TEST(ScuSession, AStopDropsTheFunctionsQueuedMove) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const double before = rig.emulator.actuator(1).position_mm();
  const ActuatorTarget t[] = {{1, 90.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 20.0, true));
  ASSERT_TRUE(rig.session.stop(1, true));
  rig.run_until(2s, [] { return false; });
  EXPECT_FALSE(rig.emulator.execution_open(1));
  EXPECT_DOUBLE_EQ(rig.emulator.actuator(1).position_mm(), before) << "the RE never went out";
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::stopped_short);
}

TEST(ScuSession, ACorruptedReplyIsRetried) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.read(0x0001));
  rig.emulator.corrupt_next_reply_crc();
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().last_read.sequence == 1; }));
  EXPECT_EQ(rig.session.health().bad_frames, 1u);
  EXPECT_EQ(rig.session.health().retries, 1u);
  EXPECT_EQ(rig.session.health().timeouts, 0u) << "retried on the bad CRC at once, not after a time-out";
  ASSERT_TRUE(rig.session.snapshot().last_read.valid);
  EXPECT_EQ(rig.session.snapshot().last_read.data_id, 0x0001);
  const auto v = rig.session.snapshot().last_read.value.view();
  ASSERT_EQ(v.size(), 31u);
  EXPECT_EQ(std::string(v.begin(), v.begin() + 8), "SCU V2B3");
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::active);
}

TEST(ScuSession, ALostReplyIsRetriedAfterTheReplyTimeout) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  rig.emulator.drop_next_replies(2);
  rig.run_until(1s, [] { return false; });
  EXPECT_EQ(rig.session.health().timeouts, 2u);
  EXPECT_EQ(rig.session.health().retries, 2u);
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::active);
  EXPECT_FALSE(rig.emulator.error_word().remote_timeout()) << "two lost replies stay inside the watchdog";
}

TEST(ScuSession, ASilentDeviceBecomesALinkFaultWithinTheConfiguredTime) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const auto cut_at = rig.clock.now();
  rig.sim.set_cut(true);
  ASSERT_TRUE(rig.run_until(5s, [&] { return rig.session.lifecycle() == Lifecycle::fault; }));
  const auto took = rig.clock.now() - cut_at;
  EXPECT_LE(took, 1000ms + 20ms) << "link_fault_after is 1000 ms";
  EXPECT_GE(took, 900ms);
  EXPECT_NE(rig.session.fault_reason().find("silent"), std::string::npos) << rig.session.fault_reason();
  EXPECT_NE(rig.session.fault_reason().find("check the cable"), std::string::npos);
}

TEST(ScuSession, ASpeedBelowTheActuatorsThresholdIsDetectedNotWaitedOn) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget t[] = {{1, 90.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 0.4, true));  // 0.4 mm/s (2 % of 20 mm/s) < 0.8 mm/s minimum
  ASSERT_TRUE(rig.run_until(2s, [&] {
    return !rig.session.snapshot().functions[0].execution_open &&
           rig.session.snapshot().functions[0].outcome != MoveOutcome::queued;
  }));
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::stopped_short);
  EXPECT_FALSE(rig.emulator.execution_open(1));
}

TEST(ScuSession, ChangesSpeedDuringTheMotion) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget t[] = {{1, 180.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 5.0, true));
  rig.run_until(3s, [] { return false; });
  EXPECT_NEAR(rig.emulator.actuator(1).velocity_mm_s(), 5.0, 1e-9);
  ASSERT_TRUE(rig.session.set_speed(1, 15.0));
  rig.run_until(1s, [] { return false; });
  EXPECT_NEAR(rig.emulator.actuator(1).velocity_mm_s(), 15.0, 1e-9) << "ramped up to the new speed";
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::running);
}

TEST(ScuSession, EmergencyStopHaltsEverythingAndDropsQueuedMoves) {
  Rig rig(2);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget t1[] = {{1, 150.0}};
  ASSERT_TRUE(rig.session.move_to(1, t1, 20.0, false));
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.emulator.actuator(1).moving(); }));
  const ActuatorTarget t2[] = {{2, 150.0}};
  ASSERT_TRUE(rig.session.move_to(2, t2, 20.0, false));
  ASSERT_TRUE(rig.session.emergency_stop());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().emergency_stop_open; }));
  EXPECT_FALSE(rig.emulator.actuator(1).active());
  EXPECT_TRUE(rig.emulator.emergency_stop_active());
  rig.run_until(1s, [] { return false; });
  EXPECT_FALSE(rig.emulator.execution_open(1)) << "the ended motion got its RS";
  EXPECT_FALSE(rig.emulator.execution_open(2)) << "the queued move was dropped";
  EXPECT_FALSE(rig.session.move_to(1, t1, 10.0, true)) << "no motion while F20 holds";
  ASSERT_TRUE(rig.session.release_emergency_stop());
  ASSERT_TRUE(rig.run_until(1s, [&] { return !rig.session.snapshot().emergency_stop_open; }));
  EXPECT_FALSE(rig.emulator.emergency_stop_active());
  EXPECT_TRUE(rig.session.move_to(1, t1, 10.0, true));
}

TEST(ScuSession, DeactivateStopsOpenMotionThenLeavesRemoteMode) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget t[] = {{1, 150.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 20.0, true));
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.emulator.execution_open(1); }));
  rig.session.deactivate(rig.clock.now());
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::deactivating);
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.lifecycle() == Lifecycle::inactive; }));
  EXPECT_FALSE(rig.emulator.execution_open(1));
  EXPECT_FALSE(rig.emulator.remote_open());
  EXPECT_FALSE(rig.session.snapshot().remote_open);
}

TEST(ScuSession, OneRcRefreshesEveryActuatorAndTheErrorWord) {
  Rig rig(6);
  ASSERT_TRUE(rig.activate());
  rig.emulator.inject_actuator_fault(5);
  const auto before = rig.session.snapshot().refreshes;
  ASSERT_TRUE(rig.run_until(200ms, [&] { return rig.session.snapshot().refreshes > before; }));
  for (int a = 1; a <= 6; ++a) {
    EXPECT_TRUE(rig.session.snapshot().actuators[static_cast<std::size_t>(a - 1)].status.present) << a;
    EXPECT_EQ(rig.session.snapshot().actuators[static_cast<std::size_t>(a - 1)].position_edges,
              rig.emulator.position_edges(a));
  }
  EXPECT_TRUE(rig.session.snapshot().errors.actuator_fault(5));
  EXPECT_EQ(rig.session.layout().read_size(), 24u + 6u + 4u);
}

TEST(ScuSession, ZeroKeepalivePeriodRefreshesAsFastAsTheLineAllows) {
  auto config = testing::session_config(1);
  config.keepalive_period = link::Duration::zero();
  Rig rig(1, config, false);
  ASSERT_TRUE(rig.activate());
  const auto before = rig.session.snapshot().refreshes;
  rig.run_until(
      1s, [] { return false; }, 100us);
  // RC 7 B + reply 5+2+4+6+4 = 21 B = 28 chars of 260.4 µs: 137 round trips per second on the wire.
  const double limit = 1.0 / (28 * 10.0 / 38400.0);
  const auto got = static_cast<double>(rig.session.snapshot().refreshes - before);
  EXPECT_GT(got, 0.9 * limit);
  EXPECT_LE(got, limit + 1);
}

TEST(ScuSession, AnUnansweredActivationIsAFaultNamingTheCommand) {
  Rig rig(1);
  rig.session.activate(rig.clock.now());
  rig.emulator.drop_next_replies(100);
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.lifecycle() == Lifecycle::fault; }));
  EXPECT_NE(rig.session.fault_reason().find("RO"), std::string::npos) << rig.session.fault_reason();
}

TEST(ScuSession, RejectsCommandsItCannotCarryOut) {
  Rig rig(2);
  const ActuatorTarget t[] = {{1, 1.0}};
  EXPECT_FALSE(rig.session.move_to(1, t, 10.0, true)) << "not active yet";
  ASSERT_TRUE(rig.activate());
  EXPECT_FALSE(rig.session.move_to(3, t, 10.0, true)) << "F3 is not defined";
  EXPECT_FALSE(rig.session.move_to(2, t, 10.0, true)) << "F2 moves A2, not A1";
  EXPECT_FALSE(rig.session.move_to(1, t, 0.0, true)) << "a speed must be above 0";
  EXPECT_FALSE(rig.session.read(0x0017)) << "no such data ID";
  EXPECT_TRUE(rig.session.move_to(1, t, 10.0, true));
  EXPECT_FALSE(rig.session.move_to(1, t, 10.0, true)) << "a move is already queued";
  EXPECT_THROW(Session(rig.sim.master(),
                       [] {
                         auto c = testing::session_config(1);
                         c.keepalive_period = 600ms;
                         return c;
                       }()),
               std::invalid_argument);
}

TEST(ScuSession, AnEmergencyStopOvertakesTheRetriesOfALostReply) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget far[] = {{1, 150.0}};
  ASSERT_TRUE(rig.session.move_to(1, far, 20.0, true));
  ASSERT_TRUE(rig.run_until(2s, [&] { return rig.session.snapshot().actuators[0].status.motion_active; }));
  // The replies to the next two requests are lost; an emergency stop comes while the first waits.
  rig.emulator.drop_next_replies(2);
  ASSERT_TRUE(rig.session.read(0x0011));
  cellctl::testing::run_for(rig.clock, 1ms, 50ms,
                            [&](link::TimePoint t) { rig.step(t); });  // the read is out
  const auto asked = rig.clock.now();
  ASSERT_TRUE(rig.session.emergency_stop());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.emulator.emergency_stop_active(); }));
  // One reply time-out (150 ms) and the F20 on the line — not the retries of the lost request first.
  EXPECT_LE(rig.clock.now() - asked, 200ms);
  EXPECT_FALSE(rig.emulator.actuator(1).active()) << "the motion stopped";
}

}  // namespace
}  // namespace cellctl::scu

// scu::Session against error replies (manual: status byte CSE/PDE/PCE/ICE/PE instead of ACK) from the
// emulator over a SimLink, in virtual time: each refusal is reported where it belongs, and only an
// ACK counts as a sign of life.

#include <gtest/gtest.h>

#include <algorithm>

#include "scu/session.hpp"
#include "scu_rig.hpp"

namespace cellctl::scu {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;
using testing::Rig;

TEST(ScuSessionRefusal, ARefusedExecuteMarksTheMoveRefusedAndTheLinkStaysUp) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  rig.emulator.refuse_next_requests(1, Status::parameter_data_error, Command::execute);
  const ActuatorTarget t[] = {{1, 50.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 10.0, true));
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().refusals > 0; }));
  const auto& s = rig.session.snapshot();
  EXPECT_EQ(s.functions[0].outcome, MoveOutcome::refused);
  EXPECT_FALSE(s.functions[0].execution_open);
  ASSERT_TRUE(s.last_refusal.has_value());
  EXPECT_EQ(s.last_refusal->command, Command::execute);
  EXPECT_EQ(s.last_refusal->status, Status::parameter_data_error);
  EXPECT_EQ(rig.session.health().error_replies, 1u);
  rig.run_until(500ms, [] { return false; });
  EXPECT_FALSE(rig.emulator.execution_open(1));
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::active) << "a refused move is no link fault";
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::refused) << "stays reported";
  // The function can be moved again once the refusal is seen.
  ASSERT_TRUE(rig.session.move_to(1, t, 10.0, true));
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.emulator.execution_open(1); }));
}

TEST(ScuSessionRefusal, ARefusedTargetPositionDropsTheRestOfTheMove) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  rig.emulator.refuse_next_requests(1, Status::permission_error, Command::transfer);
  const ActuatorTarget t[] = {{1, 50.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 10.0, true));
  rig.run_until(1s, [] { return false; });
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::refused);
  EXPECT_FALSE(rig.emulator.execution_open(1)) << "the RE after the refused RT never went out";
  EXPECT_DOUBLE_EQ(rig.emulator.actuator(1).position_mm(), 0.0);
}

TEST(ScuSessionRefusal, ARefusedKeepAliveIsAFaultSayingRemoteModeWasLost) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  rig.emulator.refuse_next_requests(1, Status::permission_error, Command::cyclic);
  ASSERT_TRUE(rig.run_until(500ms, [&] { return rig.session.lifecycle() == Lifecycle::fault; }));
  EXPECT_NE(rig.session.fault_reason().find("remote mode was lost"), std::string::npos)
      << rig.session.fault_reason();
  EXPECT_NE(rig.session.fault_reason().find("PE"), std::string::npos) << rig.session.fault_reason();
}

// An SCU that refuses RO (wrong Safety_ID, or not parameterized for remote mode) never lets the session
// become active: a fault that says why, not a retry loop and never "active".
TEST(ScuSessionRefusal, ARefusedRemoteOpenIsAFaultNamingTheSettingsToCheck) {
  Rig rig(1);
  rig.emulator.refuse_next_requests(1, Status::permission_error, Command::open);
  rig.session.activate(rig.clock.now());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.lifecycle() == Lifecycle::fault; }));
  EXPECT_NE(rig.session.fault_reason().find("refused with PE"), std::string::npos)
      << rig.session.fault_reason();
  EXPECT_NE(rig.session.fault_reason().find("entering remote mode"), std::string::npos)
      << rig.session.fault_reason();
  EXPECT_FALSE(rig.session.snapshot().remote_open);
  rig.run_until(500ms, [] { return false; });
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::fault) << "stays in fault until activated again";
}

TEST(ScuSessionRefusal, ARefusedReadIsReportedInvalidWithItsStatus) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  // The session's own RG of actuator status 2 goes first after activation; the next is 2 s away.
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().status2_known; }));
  rig.emulator.refuse_next_requests(1, Status::invalid_command, Command::get);
  ASSERT_TRUE(rig.session.read(0x0001));
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().last_read.sequence == 1; }));
  EXPECT_FALSE(rig.session.snapshot().last_read.valid);
  EXPECT_EQ(rig.session.snapshot().last_read.status, Status::invalid_command);
  EXPECT_EQ(rig.session.lifecycle(), Lifecycle::active);
}

TEST(ScuSessionRefusal, AnScuAnsweringOnlyErrorsIsSilentAndFaults) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const auto from = rig.clock.now();
  // Every request from now on gets a CSE: well-formed replies, none of them an ACK.
  rig.emulator.refuse_next_requests(1'000'000, Status::checksum_error);
  const auto answered = rig.emulator.requests_answered();
  link::Duration longest_silence{};
  ASSERT_TRUE(rig.run_until(3s, [&] {
    longest_silence = std::max(longest_silence, rig.session.silent_for(rig.clock.now()));
    return rig.session.lifecycle() == Lifecycle::fault;
  }));
  EXPECT_GT(rig.emulator.requests_answered(), answered) << "the SCU kept answering";
  EXPECT_GT(rig.session.health().error_replies, 3u);
  EXPECT_GT(longest_silence, 1000ms) << "error replies do not reset the link's silence";
  const auto took = rig.clock.now() - from;
  EXPECT_LE(took, 1000ms + 20ms) << "link_fault_after 1000 ms from the last ACK, which came before `from`";
  EXPECT_NE(rig.session.fault_reason().find("silent"), std::string::npos) << rig.session.fault_reason();
}

}  // namespace
}  // namespace cellctl::scu

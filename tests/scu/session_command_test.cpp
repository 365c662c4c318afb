// scu::Session's commands refused before anything goes on the line, each with its cause
// (scu/command_result.hpp), and nothing of a refused command left behind: the next good one is taken
// and moves the actuator as if the refusal had not been.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scu/session.hpp"
#include "scu_rig.hpp"

namespace cellctl::scu {
namespace {

using namespace std::chrono_literals;
using testing::Rig;

TEST(ScuSessionCommand, RefusedBeforeActivationAsNotActiveWhichPasses) {
  Rig rig(1);
  const ActuatorTarget t[] = {{1, 50.0}};
  const auto r = rig.session.move_to(1, t, 10.0, true);
  EXPECT_EQ(r.status, CommandStatus::not_active);
  EXPECT_TRUE(r.worth_retrying());
  EXPECT_EQ(rig.session.stop(1, true).status, CommandStatus::not_active);
  EXPECT_EQ(rig.session.emergency_stop().status, CommandStatus::not_active);
  EXPECT_EQ(rig.session.set_speed(1, 5.0).status, CommandStatus::not_active);
  EXPECT_EQ(rig.session.read(0x0001).status, CommandStatus::not_active);
}

TEST(ScuSessionCommand, AMoveTheConfigCannotMakeIsRefusedForGood) {
  Rig rig(2);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget on1[] = {{1, 50.0}};
  const ActuatorTarget on2[] = {{2, 50.0}};
  const ActuatorTarget both[] = {{1, 50.0}, {2, 50.0}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const struct {
    CommandResult result;
    CommandStatus expected;
  } cases[] = {
      {rig.session.move_to(3, on1, 10.0, true), CommandStatus::unknown_function},
      {rig.session.move_to(0, on1, 10.0, true), CommandStatus::unknown_function},
      {rig.session.move_to(11, on1, 10.0, true), CommandStatus::unknown_function},
      {rig.session.move_to(1, on1, 0.0, true), CommandStatus::bad_speed},
      {rig.session.move_to(1, on1, nan, true), CommandStatus::bad_speed},
      {rig.session.move_to(1, on2, 10.0, true), CommandStatus::wrong_actuators},
      {rig.session.move_to(1, both, 10.0, true), CommandStatus::wrong_actuators},
      {rig.session.move_to(1, {}, 10.0, true), CommandStatus::wrong_actuators},
      {rig.session.set_speed(4, 10.0), CommandStatus::unknown_function},
      {rig.session.set_speed(1, -1.0), CommandStatus::bad_speed},
      {rig.session.stop(7, true), CommandStatus::unknown_function},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(c.result.status, c.expected) << to_string(c.expected);
    EXPECT_FALSE(c.result.worth_retrying()) << to_string(c.expected);
  }
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::none);
}

TEST(ScuSessionCommand, ATargetBeyondThePositionRangeLeavesTheFunctionAsItWas) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  for (const double mm : {1e12, -1e12, std::numeric_limits<double>::infinity()}) {
    const ActuatorTarget far[] = {{1, mm}};
    const auto r = rig.session.move_to(1, far, 10.0, true);
    EXPECT_EQ(r.status, CommandStatus::target_out_of_range) << mm;
    EXPECT_FALSE(r.worth_retrying());
  }
  const auto& fs = rig.session.snapshot().functions[0];
  EXPECT_EQ(fs.outcome, MoveOutcome::none);
  EXPECT_EQ(fs.targets[0], 0) << "a refused target is not kept";
  const ActuatorTarget t[] = {{1, 20.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 20.0, true));
  ASSERT_TRUE(rig.run_until(3s, [&] { return fs.outcome == MoveOutcome::arrived; }));
  EXPECT_NEAR(rig.emulator.actuator(1).position_mm(), 20.0, 0.2);
}

TEST(ScuSessionCommand, ASecondMoveWhileTheFirstIsOpenIsBusyAndPasses) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const ActuatorTarget t[] = {{1, 20.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 20.0, true).taken());
  const auto again = rig.session.move_to(1, t, 20.0, true);
  EXPECT_EQ(again.status, CommandStatus::function_busy);
  EXPECT_TRUE(again.worth_retrying());
  const auto& fs = rig.session.snapshot().functions[0];
  ASSERT_TRUE(rig.run_until(3s, [&] { return fs.outcome == MoveOutcome::arrived && !fs.execution_open; }));
  EXPECT_TRUE(rig.session.move_to(1, t, 20.0, true).taken()) << "taken once the RE is closed";
}

TEST(ScuSessionCommand, AnEmergencyStopHoldsMovesUntilItIsReleased) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  EXPECT_EQ(rig.session.release_emergency_stop().status, CommandStatus::no_emergency_stop);
  ASSERT_TRUE(rig.session.emergency_stop().taken());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().emergency_stop_open; }));
  const ActuatorTarget t[] = {{1, 20.0}};
  const auto r = rig.session.move_to(1, t, 20.0, true);
  EXPECT_EQ(r.status, CommandStatus::emergency_stop_holds);
  EXPECT_TRUE(r.worth_retrying());
  ASSERT_TRUE(rig.session.release_emergency_stop().taken());
  ASSERT_TRUE(rig.run_until(1s, [&] { return !rig.session.snapshot().emergency_stop_open; }));
  EXPECT_TRUE(rig.session.move_to(1, t, 20.0, true).taken());
}

// The cell asks for the release every cycle until the SCU has answered it: one RS F20 goes out, not
// one per cycle (on a slow line a few dozen would fill the queue the stops need).
TEST(ScuSessionCommand, AReleaseAskedEveryCycleGoesOutOnce) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  ASSERT_TRUE(rig.session.emergency_stop().taken());
  ASSERT_TRUE(rig.run_until(1s, [&] { return rig.session.snapshot().emergency_stop_open; }));
  // Every request but the keep-alive's RC is counted by the replies it got beside the RCs.
  const auto others = [&] { return rig.session.health().good_replies - rig.emulator.cyclic_count(); };
  const auto before = others();
  int asked = 0;
  ASSERT_TRUE(rig.run_until(1s, [&] {
    if (!rig.session.snapshot().emergency_stop_open) return true;
    EXPECT_TRUE(rig.session.release_emergency_stop().taken());
    ++asked;
    return false;
  }));
  EXPECT_GT(asked, 3);
  rig.run_until(500ms, [] { return false; });
  EXPECT_EQ(others() - before, 1u) << "releases sent for " << asked << " asked";
  const ActuatorTarget t[] = {{1, 20.0}};
  EXPECT_TRUE(rig.session.move_to(1, t, 20.0, true).taken());
  EXPECT_TRUE(rig.session.stop(1, true).taken());
}

TEST(ScuSessionCommand, AFullQueueRefusesWhatDoesNotFitWhole) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  // Each change of speed queues one RT; nothing goes out while no cycle runs.
  int taken = 0;
  CommandResult r;
  for (int i = 0; i < 100 && (r = rig.session.set_speed(1, i % 2 == 0 ? 5.0 : 10.0)).taken(); ++i) ++taken;
  EXPECT_EQ(r.status, CommandStatus::queue_full);
  EXPECT_TRUE(r.worth_retrying());
  EXPECT_GT(taken, 10);
  const ActuatorTarget t[] = {{1, 20.0}};
  EXPECT_EQ(rig.session.move_to(1, t, 20.0, true).status, CommandStatus::queue_full);
  EXPECT_EQ(rig.session.read(0x0001).status, CommandStatus::queue_full);
  EXPECT_EQ(rig.session.snapshot().functions[0].outcome, MoveOutcome::none) << "no part of the move queued";
  EXPECT_TRUE(rig.session.stop(1, true).taken()) << "stops have a queue of their own";
}

TEST(ScuSessionCommand, AReadOfAnUnknownDataIdIsRefused) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());
  const auto r = rig.session.read(0xFFFF);
  EXPECT_EQ(r.status, CommandStatus::unknown_data_id);
  EXPECT_FALSE(r.worth_retrying());
  EXPECT_TRUE(rig.session.read(0x0001).taken());
}

TEST(ScuSessionCommand, EveryStatusHasItsOwnWords) {
  for (int s = 0; s <= static_cast<int>(CommandStatus::unknown_data_id); ++s)
    EXPECT_NE(to_string(static_cast<CommandStatus>(s)), "?") << s;
}

}  // namespace
}  // namespace cellctl::scu

// The SCU as a device of the cell (device_seam::ScuDevice) on the emulated cell over SimLinks: a move
// the session refuses for good is not asked again every cycle but read as refused at once, with the
// session's cause, so the move executor ends the step naming it (it used to wait for its time-out);
// a refusal that passes (the RS still on its way) is asked again until the move is taken.

#include <gtest/gtest.h>

#include <string>

#include "config/cell_config.hpp"
#include "support/cell_rig.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

class ScuDeviceTest : public ::testing::Test {
 protected:
  ScuDeviceTest() : rig_(config::load_cell_config(CELLCTL_SOURCE_DIR "/config/cell.yaml")) {}

  void cycle() {
    rig_.receive();
    rig_.transmit(intents_);
  }
  template <class Done>
  bool cycle_until(Done&& done, int limit = 5000) {
    for (int i = 0; i < limit; ++i) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  void start_up() {
    rig_.devices.activate(rig_.clock.now());
    ASSERT_TRUE(cycle_until([&] { return rig_.state.links[cell::slot(cell::Device::scu)].active; }));
  }
  void ask_move(std::uint32_t id, double target_mm, double speed_mm_s) {
    intents_.axes[0] = {.move_id = id,
                        .move = true,
                        .target_mm = target_mm,
                        .speed_mm_s = speed_mm_s,
                        .soft = true,
                        .planned_mm = 0.0,
                        .planned_mm_s = 0.0};
  }

  CellRig rig_;
  cell::Intents intents_;
};

TEST_F(ScuDeviceTest, AMoveTheSessionRefusesForGoodReadsRefusedAtOnceWithItsCause) {
  start_up();
  ask_move(1, 1e12, 10.0);  // beyond the SCU's 32-bit position in edges
  cycle();
  cycle();
  EXPECT_TRUE(rig_.state.axes[0].move_refused);
  EXPECT_EQ(rig_.state.scu_refusal, "a target is beyond the SCU's position range");
  EXPECT_FALSE(rig_.state.axes[0].commanded);
  EXPECT_FALSE(rig_.state.axes[1].move_refused) << "the other axis has nothing to do with it";

  // The next move is asked for, taken, and the refusal is history.
  ask_move(2, 10.0, 10.0);
  ASSERT_TRUE(cycle_until([&] { return rig_.state.axes[0].moves_taken == 1; }));
  EXPECT_FALSE(rig_.state.axes[0].move_refused);
  ASSERT_TRUE(
      cycle_until([&] { return !rig_.state.axes[0].commanded && !rig_.state.axes[0].moving; }, 10000));
  EXPECT_NEAR(rig_.state.axes[0].scu_mm, 10.0, 0.2);
}

TEST_F(ScuDeviceTest, ANewTargetWhileTheAxisMovesIsAskedAgainUntilItsRsIsThrough) {
  start_up();
  ask_move(1, 50.0, 20.0);
  ASSERT_TRUE(cycle_until([&] { return rig_.state.axes[0].moving; }));
  // The RS goes first; the session refuses the move as busy until it is through, then takes it.
  ask_move(2, 20.0, 20.0);
  ASSERT_TRUE(cycle_until([&] { return rig_.state.axes[0].moves_taken == 2; }));
  EXPECT_FALSE(rig_.state.axes[0].move_refused);
  ASSERT_TRUE(
      cycle_until([&] { return !rig_.state.axes[0].commanded && !rig_.state.axes[0].moving; }, 10000));
  EXPECT_NEAR(rig_.state.axes[0].scu_mm, 20.0, 0.2);
}

}  // namespace
}  // namespace cellctl::testing

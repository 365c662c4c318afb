// Homing end to end in virtual time, through the real sessions, emulators and simulated lines: each
// strategy, sequences, an abort mid-homing, homing twice, the home record written and checked by
// `require: homed` in the next process (a fresh CellRun), and what breaks it: an SCU that lost power,
// an encoder replaced, a changed config. Each test has its own state folder and encoder EEPROM.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "encoder/eeprom_file.hpp"
#include "journal/record_header.hpp"
#include "run_fixture.hpp"
#include "runtime/home_record_file.hpp"

namespace cellctl::testing {
namespace {

using config::HomingStrategy;

const std::string kHead = R"(recipe: {name: homing, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
    z: {min_mm: 0, max_mm: 130, max_speed_mm_s: 12, tolerance_mm: 0.1}
  spindle: {min_hz: 200, max_hz: 600}
steps:
)";

class HomingTest : public RunFixture {
 protected:
  runtime::RunResult run_steps(const std::string& steps) {
    load_recipe_text(kHead + steps);
    make_run();
    return go();
  }
  routines::HomeRecord record() const {
    return runtime::load_home_record(runtime::home_record_path(dir_ / "state", "virtual-time"), cell_,
                                     journal::file_sha256(cell_.source));
  }
  // A new process with new emulators: the SCU's actuators as the emulator config says (after a
  // power loss: not initialised), the encoder's EEPROM from its file.
  void next_process() {
    emulators_.reset();
    std::filesystem::remove_all(dir_ / "journal");
  }
};

TEST_F(HomingTest, EndPositionDrivesIntoTheEndPresetsTheEncoderAndGoesHome) {
  const auto r = run_steps("  - move: {to: {x: 40}, speed_mm_s: 15}\n  - home: [x]\n");
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  EXPECT_NEAR(run_->state().axes[0].encoder_mm, 5.0, 0.1);
  EXPECT_EQ(notes_with("home x: at the end (SCU 0.00 mm"), 1u);
  EXPECT_EQ(notes_with("home x: encoder preset to 0.000 mm, reads 0.000 mm"), 1u);
  const auto rec = record();
  ASSERT_TRUE(rec.axes[0].homed);
  EXPECT_EQ(rec.axes[0].strategy, HomingStrategy::end_position);
  EXPECT_TRUE(rec.axes[0].measured);
  EXPECT_NEAR(rec.axes[0].encoder_mm, 5.0, 0.1);
  EXPECT_NEAR(rec.axes[0].scu_mm, 5.0, 0.1);
  EXPECT_FALSE(rec.axes[1].homed);
  EXPECT_GT(rec.axes[0].unix_time, 0);
}

TEST_F(HomingTest, ScuInitialisedDrivesANotInitialisedActuatorIntoItsRetractedEnd) {
  ASSERT_FALSE(emulators().scu->initialised[1]) << "the emulated SCU starts as after power-up";
  const auto r = run_steps("  - home: [z]\n");
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  EXPECT_TRUE(run_->emulators()->scu()->initialised(2));
  EXPECT_TRUE(run_->state().axes[1].scu_initialised);
  EXPECT_NEAR(run_->state().axes[1].scu_mm, 5.0, 0.1);
  EXPECT_EQ(notes_with("home z: backing off the end"), 1u) << "z stood in its end at power-up";
  const auto rec = record();
  ASSERT_TRUE(rec.axes[1].homed);
  EXPECT_EQ(rec.axes[1].strategy, HomingStrategy::scu_initialised);
  EXPECT_FALSE(rec.axes[1].measured);
}

TEST_F(HomingTest, ScuInitialisedAlreadyInitialisedOnlyGoesHome) {
  emulators().scu->initialised = {true, true};
  const auto r = run_steps("  - move: {to: {z: 30}, speed_mm_s: 10}\n  - home: [z]\n");
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  EXPECT_EQ(notes_with("home z: to the end"), 0u);
  EXPECT_NEAR(run_->state().axes[1].scu_mm, 5.0, 0.1);
}

TEST_F(HomingTest, AbsoluteEncoderHomesWithoutMotion) {
  cell_.axes[0].homing = {.strategy = HomingStrategy::absolute_encoder};
  double farthest = 0.0;
  load_recipe_text(kHead + "  - home: [x]\n  - require: {homed: [x]}\n");
  make_run().on_cycle([&](double, runtime::CellRun& run) {
    farthest = std::max(farthest, std::abs(run.emulators()->scu()->actuator(1).position_mm()));
  });
  const auto r = go();
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  EXPECT_EQ(farthest, 0.0) << "absolute_encoder homing moves nothing";
  const auto rec = record();
  ASSERT_TRUE(rec.axes[0].homed);
  EXPECT_EQ(rec.axes[0].strategy, HomingStrategy::absolute_encoder);
}

TEST_F(HomingTest, AbsoluteEncoderThatDisagreesWithItsRecordIsRefused) {
  cell_.axes[0].homing = {.strategy = HomingStrategy::absolute_encoder};
  ASSERT_EQ(run_steps("  - home: [x]\n").final_state, supervisor::State::complete);
  next_process();
  emulators().plant.encoder_mount_mm = 1.0;  // another encoder, mounted 1 mm off
  const auto r = run_steps("  - home: [x]\n");
  ASSERT_EQ(r.final_state, supervisor::State::stopped) << r.failure;
  EXPECT_NE(r.failure.find("the home record expects 0.00 mm"), std::string::npos) << r.failure;
}

// An encoder preset since the config was written (another encoder, or a preset by hand) holds an
// offset the config does not expect: its session refuses it, and the run ends on that at once with
// the session's reason, not after the start time-out with "encoder down".
TEST_F(HomingTest, AnEncoderPresetSinceTheConfigIsRefusedAtOnceWithItsReason) {
  std::filesystem::create_directories(dir_);
  ASSERT_TRUE(encoder::save_eeprom(dir_ / "encoder.eeprom", {.offset = 2048}));
  const auto r = run_steps("  - home: [x]\n");
  ASSERT_EQ(r.final_state, supervisor::State::aborted) << r.failure;
  EXPECT_EQ(r.failure, "encoder session failed while starting (its reason follows)");
  EXPECT_LT(r.duration_s, 2.0) << "not the 20 s start time-out";
  const auto note = std::find_if(r.device_notes.begin(), r.device_notes.end(), [](const std::string& n) {
    return n.find("the encoder holds preset offset 2048") != std::string::npos;
  });
  EXPECT_NE(note, r.device_notes.end()) << ::testing::PrintToString(r.device_notes);
  EXPECT_EQ(run_->emulators()->scu()->actuator(1).position_mm(), 0.0) << "refused before any motion";
}

TEST_F(HomingTest, HomingTwiceGivesTheSamePositions) {
  ASSERT_EQ(run_steps("  - move: {to: {x: 60, z: 40}, speed_mm_s: 12}\n  - home: [x, z]\n").final_state,
            supervisor::State::complete);
  const auto first = record();
  next_process();
  emulators().scu->initialised = {true, true};  // the same SCU, still powered
  const auto r = run_steps("  - move: {to: {x: 120, z: 90}, speed_mm_s: 12}\n  - home: [x, z]\n");
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  const auto second = record();
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_TRUE(first.axes[i].homed && second.axes[i].homed);
    EXPECT_NEAR(second.axes[i].scu_mm, first.axes[i].scu_mm, 0.05) << i;
    EXPECT_NEAR(second.axes[i].encoder_mm, first.axes[i].encoder_mm, 0.05) << i;
  }
  // Nothing applied twice: the encoder still reads what it read after the first preset.
  EXPECT_NEAR(run_->state().axes[0].encoder_mm, 5.0, 0.1);
}

TEST_F(HomingTest, ARecipeHomesThenRequiresHomedThenMoves) {
  const auto r = run_steps(R"(  - home: [x, z]
  - require: {homed: [x, z]}
  - move: {to: {x: 50, z: 20}, speed_mm_s: 10}
)");
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure;
  EXPECT_NEAR(run_->state().axes[0].encoder_mm, 50.0, 0.1);
  EXPECT_NE(r.home_record.find("home record written"), std::string::npos);
  EXPECT_NE(r.home_record.find("home.virtual-time.json"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "state" / "home.json"))
      << "a dry run leaves the cell's record alone";
}

TEST_F(HomingTest, AbortMidHomingStopsEveryMovingAxis) {
  cell_.axes[1].homing.sequence = 0;  // x and z home together
  std::optional<double> aborted_at;
  std::array<double, 2> at_abort{};
  load_recipe_text(kHead + "  - move: {to: {x: 60, z: 60}, speed_mm_s: 12}\n  - home: [x, z]\n");
  make_run().on_cycle([&](double t, runtime::CellRun& run) {
    auto* scu = run.emulators()->scu();
    const bool homing = run.supervisor().current() &&
                        std::holds_alternative<recipe::Home>(run.supervisor().current()->action);
    if (!aborted_at && homing && scu->actuator(1).position_mm() < 50.0 &&
        scu->actuator(2).position_mm() < 50.0) {
      aborted_at = t;
      at_abort = {scu->actuator(1).position_mm(), scu->actuator(2).position_mm()};
      run.request(supervisor::Command::abort);
    }
  });
  const auto r = go();
  ASSERT_TRUE(aborted_at) << "homing never had both axes moving";
  EXPECT_EQ(r.final_state, supervisor::State::aborted);
  auto* scu = run_->emulators()->scu();
  for (int a = 1; a <= 2; ++a) {
    EXPECT_FALSE(scu->actuator(a).active()) << "actuator " << a << " still moving";
    // Category 0 (abort): fast stop; at 5 mm/s it ends within a few tenths of a mm.
    EXPECT_NEAR(scu->actuator(a).position_mm(), at_abort[static_cast<std::size_t>(a - 1)], 0.5) << a;
    EXPECT_GT(scu->actuator(a).position_mm(), 10.0) << "stopped before its end";
  }
  const auto rec = record();
  EXPECT_FALSE(rec.axes[0].homed) << "a homing aborted midway leaves the axes not homed";
  EXPECT_FALSE(rec.axes[1].homed);
}

TEST_F(HomingTest, ASpindleThatTurnsRefusesHomingBeforeAnyMotion) {
  const auto r = run_steps("  - spindle: {start_hz: 300}\n  - home: [x]\n");
  ASSERT_EQ(r.final_state, supervisor::State::stopped);
  EXPECT_NE(r.failure.find("not homing: the spindle turns"), std::string::npos) << r.failure;
  EXPECT_EQ(run_->emulators()->scu()->actuator(1).position_mm(), 0.0);
}

// The next process checks the record against the devices: it holds on the same, powered SCU; an SCU
// that lost power (its actuators no longer initialised) breaks it, and so does a replaced encoder.
class HomedInTheNextProcess : public HomingTest {
 protected:
  void SetUp() override {
    HomingTest::SetUp();
    ASSERT_EQ(run_steps("  - home: [x, z]\n").final_state, supervisor::State::complete);
    next_process();
  }
  const std::string kRequire = "  - require: {homed: [x, z]}\n  - move: {to: {x: 30}, speed_mm_s: 10}\n";
};

TEST_F(HomedInTheNextProcess, HoldsOnTheSamePoweredScu) {
  emulators().scu->initialised = {true, true};
  // (The emulated actuators start at 0 mm, where homing left them 5 mm: moved by hand while off.)
  const auto r = run_steps(kRequire);
  EXPECT_EQ(r.final_state, supervisor::State::complete) << r.failure;
}

TEST_F(HomedInTheNextProcess, AnScuPowerLossBreaksIt) {
  // A fresh emulated SCU is one that lost power: no actuator initialised.
  const auto r = run_steps(kRequire);
  ASSERT_EQ(r.final_state, supervisor::State::stopped);
  EXPECT_EQ(
      r.failure,
      "axis x: the SCU reports actuator 1 not initialised (power loss or reset since homing): home it again");
  EXPECT_EQ(run_->emulators()->scu()->actuator(1).position_mm(), 0.0) << "refused before any motion";
}

TEST_F(HomedInTheNextProcess, AReplacedEncoderBreaksIt) {
  emulators().scu->initialised = {true, true};
  emulators().plant.encoder_mount_mm = 1.0;  // another encoder, mounted to read 1 mm more
  const auto r = run_steps(kRequire);
  ASSERT_EQ(r.final_state, supervisor::State::stopped) << r.failure;
  EXPECT_NE(r.failure.find("axis x: encoder at 1.00 mm, home record expects "), std::string::npos)
      << r.failure;
  EXPECT_EQ(run_->emulators()->scu()->actuator(1).position_mm(), 0.0) << "refused before any motion";
}

TEST_F(HomedInTheNextProcess, AHomingAbortedMidwayLeavesTheAxisNotHomedAndTheOthersAsTheyWere) {
  // Homed in the last process; homing x again is aborted midway: the old home of x no longer holds
  // (the rod may have been moved since it was found), so the record says x is not homed, and the next
  // run's `require: homed` refuses it. z, not homed again, keeps its home (issue 22: a homing that
  // starts clears its axes' record first; deleting that line failed no test).
  emulators().scu->initialised = {true, true};
  load_recipe_text(kHead + "  - move: {to: {x: 60}, speed_mm_s: 12}\n  - home: [x]\n");
  bool aborted = false;
  make_run().on_cycle([&](double, runtime::CellRun& run) {
    const auto* ins = run.supervisor().current();
    const bool homing = ins && std::holds_alternative<recipe::Home>(ins->action);
    if (!aborted && homing && run.emulators()->scu()->actuator(1).position_mm() < 50.0) {
      aborted = true;
      run.request(supervisor::Command::abort);
    }
  });
  ASSERT_EQ(go().final_state, supervisor::State::aborted);
  ASSERT_TRUE(aborted) << "homing never moved x";
  const auto rec = record();
  EXPECT_FALSE(rec.axes[0].homed) << "x keeps a home that its aborted homing no longer vouches for";
  EXPECT_TRUE(rec.axes[1].homed) << "z was not homed again: its home holds";
  next_process();
  emulators().scu->initialised = {true, true};
  const auto r = run_steps(kRequire);
  ASSERT_EQ(r.final_state, supervisor::State::stopped);
  EXPECT_NE(r.failure.find("axis x"), std::string::npos) << r.failure;
}

TEST_F(HomedInTheNextProcess, AChangedConfigBreaksIt) {
  emulators().scu->initialised = {true, true};
  load_recipe_text(kHead + kRequire);
  auto changed = dir_ / "changed.yaml";
  std::filesystem::copy_file(cell_.source, changed);
  { std::ofstream(changed, std::ios::app) << "# edited\n"; }
  cell_.source = changed;
  make_run();
  const auto r = go();
  ASSERT_EQ(r.final_state, supervisor::State::stopped);
  EXPECT_EQ(r.failure, "axis x: the cell config changed since it was homed: home it again");
}

}  // namespace
}  // namespace cellctl::testing

// cellctl serve's look at the cell before its first job (runtime/cell_look.hpp), in virtual time on
// the emulated demo cell: it reads the plant as a dry run left it — each actuator where it stands,
// initialised or not — and moves nothing: the plant is kept as it was found.

#include "runtime/cell_look.hpp"

#include <gtest/gtest.h>

#include "run_fixture.hpp"
#include "runtime/dry_run_state.hpp"
#include "runtime/plant_state.hpp"

namespace cellctl::testing {
namespace {

class CellLook : public RunFixture {};

TEST_F(CellLook, ReadsTheCellAsItStandsAndMovesNothing) {
  // The plant as the last dry run left it: x at 42.0 mm and initialised, z at 17.3 mm and not.
  const auto state_dir = dir_ / "state";
  runtime::PlantState kept;
  kept.actuators[0] = runtime::PlantState::Actuator{42.0, true};
  kept.actuators[1] = runtime::PlantState::Actuator{17.3, false};
  ASSERT_TRUE(runtime::save_plant_state(runtime::dry_run_plant_file(state_dir), kept));
  runtime::LookOptions o;
  o.mode = runtime::RunMode::virtual_time;
  o.state_dir = state_dir;
  o.emulators = runtime::dry_run_emulator_setup(cell_, state_dir);
  o.emulators->encoder->state_file = dir_ / "encoder.eeprom";

  const auto look = runtime::look_at_cell(cell_, o);

  EXPECT_TRUE(look.answered) << look.words;
  EXPECT_EQ(look.words.rfind("x 42.0 mm, z 17.3 mm; encoder ", 0), 0u) << look.words;
  EXPECT_NEAR(look.view.scu_mm[0], 42.0, 0.05);
  EXPECT_NEAR(look.view.scu_mm[1], 17.3, 0.05);
  EXPECT_TRUE(look.view.scu_initialised[0]);
  EXPECT_FALSE(look.view.scu_initialised[1]);
  EXPECT_TRUE(look.view.encoder_measures[0]);
  EXPECT_EQ(look.view.state, supervisor::State::idle);
  EXPECT_EQ(look.view.steps, 0u);
  EXPECT_LT(look.view.t, 1.0) << "every device answers within a second of virtual time";
  // The journal's sample says the same, each axis planned where it stands, no spindle speed asked for.
  EXPECT_FLOAT_EQ(look.sample.scu_mm[0], static_cast<float>(look.view.scu_mm[0]));
  EXPECT_FLOAT_EQ(look.sample.planned_mm[1], static_cast<float>(look.view.scu_mm[1]));
  EXPECT_EQ(look.sample.spindle_set_hz, 0.0f);
  // Nothing moved: the emulated plant is kept as the look found it.
  const auto after = runtime::load_plant_state(runtime::dry_run_plant_file(state_dir));
  ASSERT_TRUE(after.actuators[0] && after.actuators[1]);
  EXPECT_DOUBLE_EQ(after.actuators[0]->position_mm, 42.0);
  EXPECT_DOUBLE_EQ(after.actuators[1]->position_mm, 17.3);
  EXPECT_TRUE(after.actuators[0]->initialised);
  EXPECT_FALSE(after.actuators[1]->initialised);
}

}  // namespace
}  // namespace cellctl::testing

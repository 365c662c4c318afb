// The emulated encoder's shaft turns with the axis at the lead the session takes a revolution to be,
// also when the encoder reports scaled measuring units (scaling: true) rather than physical steps:
// after a move the encoder reads where the rod really is.

#include <string>

#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

constexpr const char* kScaledMoveRecipe = R"(
recipe: {name: one-move, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 30}
steps:
  - {name: out, move: {to: {x: 60}, speed_mm_s: 15}}
)";

class EncoderScaling : public FaultRun {};

TEST_F(EncoderScaling, ScaledUnitsPerRevolutionReadTheTruePosition) {
  // 1000 measuring units per revolution of the 8192-step singleturn, 250 units per mm: 4 mm per
  // revolution, as the shipped cell — but in scaled units, not steps (8192 / 250 would be 32.8 mm).
  auto& session = cell_.encoder->session;
  ASSERT_EQ(session.physical.steps_per_revolution, 8192u);
  session.parameters.scaling = true;
  session.parameters.units_select = encoder::UnitsSelect::per_revolution;
  session.parameters.measuring_units = 1000;
  session.parameters.total_range = 1000u * session.physical.revolutions;
  session.mm_per_revolution = 0.0;
  session.counts_per_mm = 250.0;
  emulators().scu->actuators[0].physics.scale_error = 0.0;
  load_recipe_text(kScaledMoveRecipe);

  const auto r = run_with([](double, runtime::CellRun&) { return true; });
  EXPECT_EQ(r.final_state, supervisor::State::complete) << r.failure << "\n" << r.summary_text;
  const double true_mm = run_->emulators()->scu()->actuator(1).true_position_mm();
  const double encoder_mm = run_->state().axes[0].encoder_mm;
  std::cout << "  scaled encoder " << encoder_mm << " mm, rod " << true_mm << " mm\n";
  EXPECT_NEAR(true_mm, 60.0, 0.1) << "the rod moved";
  // One measuring unit is 0.004 mm.
  EXPECT_NEAR(encoder_mm, true_mm, 0.004) << "the encoder reads where the rod is";
  EXPECT_TRUE(events("fault").empty()) << r.summary_text;
}

}  // namespace
}  // namespace cellctl::testing

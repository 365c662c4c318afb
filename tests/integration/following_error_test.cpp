// The following-error rule (LinuxCNC's MIN_FERROR/FERROR) on the whole emulated cell in virtual time:
// the shipped demo stays well inside its allowance, and an axis that cannot keep up with its plan —
// stalled, or physically slower than the SCU is told — latches following_error in its stop category.

#include <algorithm>
#include <cmath>
#include <iostream>

#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

using supervisor::State;

class FollowingError : public FaultRun {
 protected:
  // The largest |planned − measured| ÷ allowed seen over the run, per axis.
  std::array<double, 2> worst_{};
  void watch(runtime::CellRun& run) {
    const auto& in = run.supervisor().intents();
    if (in.halt != cell::Halt::none) return;
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& a = in.axes[i];
      if (!a.move) continue;
      const double err = std::abs(a.planned_mm - run.state().axes[i].position_mm());
      worst_[i] = std::max(worst_[i], err / config::allowed_following_error(cell_.axes[i], a.planned_mm_s));
    }
  }
};

TEST_F(FollowingError, TheDemoStaysWellInsideItsAllowance) {
  load_recipe(source_dir() / "recipes/demo.yaml");
  auto& run = make_run();
  run.on_cycle([this](double, runtime::CellRun& r) { watch(r); });
  const auto r = go();
  EXPECT_EQ(r.final_state, State::complete) << r.summary_text;
  std::cout << "  worst following error ÷ allowance: x " << worst_[0] << ", z " << worst_[1] << "\n";
  // Half the allowance at most: a healthy cell never comes near it.
  EXPECT_LT(worst_[0], 0.5);
  EXPECT_LT(worst_[1], 0.5);
}

TEST_F(FollowingError, AStalledAxisLatchesFollowingErrorLongBeforeNoMotion) {
  // x's real threshold is 5 mm/s; moved at 3 mm/s it does not move at all.
  emulators().scu->actuators[0].physics.min_speed_mm_s = 5.0;
  load_recipe_text(kCreepRecipe);
  const auto r = run_with([](double, runtime::CellRun&) { return true; });
  const auto f = fault("following_error");
  ASSERT_FALSE(f.is_null()) << r.summary_text;
  EXPECT_EQ(f["category"], static_cast<int>(cell_.stops.following_error));
  // At 3 mm/s on a 20 mm/s axis the allowance is max(min_ferror, ferror × 3/20): the plan gets that
  // far ahead after its ramp; the no-motion check would take 1.5 s.
  const double allowed = config::allowed_following_error(cell_.axes[0], 3.0);
  std::cout << "  stalled x: following_error after " << f["t"].get<double>() << " s (allowed " << allowed
            << " mm): " << f["detail"].get<std::string>() << "\n";
  EXPECT_LT(f["t"].get<double>(), supervisor_settings_.move.no_motion_s);
  EXPECT_EQ(r.final_state, State::stopped) << r.summary_text;
  expect_axes_at_rest();
}

TEST_F(FollowingError, AnAxisSlowerThanTheScuIsToldFallsBehindItsPlan) {
  // z's motor reaches only 2 mm/s (worn, overloaded) while the SCU's 100 % is taken for 15 mm/s.
  emulators().scu->actuators[1].physics.max_speed_mm_s = 2.0;
  load_recipe_text(kTraverseRecipe);
  const auto r = run_with([this](double, runtime::CellRun& run) {
    // The cause: the true lag behind the plan exceeds what its planned speed allows.
    const auto& a = run.supervisor().intents().axes[1];
    if (!a.move) return false;
    const double lag = std::abs(a.planned_mm - run.emulators()->scu()->actuator(2).true_position_mm());
    return lag > config::allowed_following_error(cell_.axes[1], a.planned_mm_s);
  });
  report("following_error", 300.0);
  const auto f = fault("following_error");
  ASSERT_FALSE(f.is_null()) << r.summary_text;
  // z is known by the SCU's position, refreshed every 100 ms with its reply; the monitor allows for
  // the plan's travel since, so it sees the lag within two refreshes of the plant.
  EXPECT_LE(reaction_ms("following_error"), 300.0);
  EXPECT_EQ(r.final_state, State::stopped) << r.summary_text;
  expect_axes_at_rest();
}

}  // namespace
}  // namespace cellctl::testing

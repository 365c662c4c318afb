// The whole control cycle — sessions, emulators, monitor, supervisor, journal posting — allocates
// nothing on the loop's thread once the recipe executes: counted from the first cycle in Execute to
// the last, over a short recipe with the spindle, coordinated moves and a dwell, in virtual time.

#include <optional>
#include <string>

#include "run_fixture.hpp"
#include "support/execute_window.hpp"

namespace cellctl::testing {
namespace {

const std::string kShortRecipe =
    demo_recipe("short", R"(  - {name: spindle up, spindle: {start_hz: 400, direction: cw}}
  - {name: out, move: {to: {x: 40, z: 20}, speed_mm_s: 12}}
  - {name: pause, dwell: 0.5}
  - {name: back, move: {to: {x: 5, z: 5}, speed_mm_s: 12}}
  - {name: spindle down, spindle: stop}
)");

TEST_F(RunFixture, ExecuteCyclesAllocateNothing) {
  load_recipe_text(kShortRecipe);
  ExecuteWindow window;
  // A zero means something only if the counter sees the loop's thread: one allocation made there,
  // in the first cycle (before the window), must be counted.
  std::string probe;
  std::size_t probe_counted = 0;
  make_run().on_cycle([&](double, runtime::CellRun& r) {
    if (probe.empty()) {
      const std::size_t before = thread_allocation_count();
      probe.assign(64, 'x');
      probe_counted = thread_allocation_count() - before;
    }
    window.on_cycle(r.supervisor().state());
  });
  const auto r = go();
  ASSERT_EQ(probe_counted, 1u) << "the allocation counter does not see the loop's thread";
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure << "\n" << r.summary_text;
  ASSERT_TRUE(window.closed) << "the run left Execute";
  EXPECT_EQ(window.ended_in, supervisor::State::completing);
  EXPECT_GT(window.cycles, 5000u) << "the window covers the recipe";
  std::cout << "  " << window.allocations() << " allocations in " << window.cycles << " Execute cycles ("
            << window.start_up() << " in start-up, " << window.after() << " after)\n";
  EXPECT_EQ(window.allocations(), 0u);
}

// A hold during a move on a line and an unhold while the axes still brake: the brake the plan
// follows, the re-plan from the moving state and the journal's note (the line is impossible from
// there) allocate nothing either, from the first cycle in Execute to Completing.
TEST_F(RunFixture, HoldAndUnholdFromMotionAllocateNothing) {
  std::string recipe = kShortRecipe;
  const std::string out = "{to: {x: 40, z: 20}, speed_mm_s: 12}";
  recipe.replace(recipe.find(out), out.size(), "{to: {x: 40, z: 20}, speed_mm_s: 12, path: line}");
  load_recipe_text(recipe);
  std::optional<std::size_t> at_execute;
  std::optional<std::size_t> at_completing;
  std::optional<double> held_at;
  bool resumed = false;
  make_run().on_cycle([&](double t, runtime::CellRun& r) {
    const auto state = r.supervisor().state();
    if (!at_execute && state == supervisor::State::execute) at_execute = thread_allocation_count();
    if (at_execute && !at_completing && state == supervisor::State::completing)
      at_completing = thread_allocation_count();
    if (!held_at && r.supervisor().step_index() == 1 && r.state().axes[0].encoder_mm > 20.0) {
      r.request(supervisor::Command::hold);
      held_at = t;
    }
    if (held_at && !resumed && t - *held_at >= 0.05) {
      EXPECT_EQ(state, supervisor::State::holding);
      r.request(supervisor::Command::unhold);
      resumed = true;
    }
  });
  const auto r = go();
  ASSERT_EQ(r.final_state, supervisor::State::complete) << r.failure << "\n" << r.summary_text;
  ASSERT_TRUE(resumed && at_execute && at_completing);
  bool noted = false;
  for (const auto& n : events("note"))
    noted =
        noted || n["text"].get<std::string>().find("phase synchronisation impossible") != std::string::npos;
  EXPECT_TRUE(noted) << "the resumed line's note was journaled";
  EXPECT_EQ(*at_completing - *at_execute, 0u);
}

}  // namespace
}  // namespace cellctl::testing

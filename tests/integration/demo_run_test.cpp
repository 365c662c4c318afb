// The shipped demo recipe on the shipped default cell, end to end in virtual time.

#include "run_fixture.hpp"

namespace cellctl::testing {
namespace {

TEST_F(RunFixture, DemoRecipeCompletes) {
  load_recipe(source_dir() / "recipes/demo.yaml");
  make_run();
  const auto r = go();
  EXPECT_EQ(r.final_state, supervisor::State::complete) << r.failure << "\n" << r.summary_text;
  EXPECT_TRUE(r.faults.empty()) << r.faults.front();
  EXPECT_FALSE(r.interrupted);
  const auto ends = events("run_ended");
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0]["outcome"], "complete");
  EXPECT_EQ(events("step_done").size(), 25u);
  EXPECT_TRUE(events("step_failed").empty());
  const auto s = run_->state();
  EXPECT_NEAR(s.axes[0].encoder_mm, 5.0, 0.1);
  EXPECT_NEAR(s.axes[1].scu_mm, 5.0, 0.1);
  EXPECT_TRUE(s.spindle.at_rest);
  std::cout << r.summary_text << "virtual " << r.duration_s << " s in " << r.wall_s << " s wall ("
            << r.duration_s / r.wall_s << "×)\n";
}

}  // namespace
}  // namespace cellctl::testing

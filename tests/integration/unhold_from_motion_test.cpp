// An unhold from a moving hold, on the whole emulated cell in virtual time: the traverse is held while
// both axes run, and the unhold comes while the SCU still brakes them. The move goes on from that
// moving state (no stop first) and reaches its target sooner than the old way could: wait until Held
// (the axes at rest, as the SCU reports it), then unhold and start again from rest. Both are measured
// from the same hold, to the moment both rods are at their targets (within the recipe's 0.1 mm) and
// at rest in the plant.

#include <algorithm>
#include <iostream>
#include <optional>

#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

using supervisor::Command;
using supervisor::State;

class UnholdFromMotion : public FaultRun {
 protected:
  void SetUp() override {
    FaultRun::SetUp();
    load_recipe_text(kTraverseRecipe);
  }

  struct Outcome {
    double arrived_s = 0.0;       // from the hold to both rods at rest on their targets
    double slowest_x_mm_s = 1e9;  // x's lowest speed from the hold to 10 mm before its target
    bool held = false;            // the supervisor went through Held
  };

  // Holds the traverse once x is past 40 mm; unholds `unhold_after_s` after the hold or, when that is
  // not given, as soon as Held is entered (stop and re-plan).
  Outcome hold_and_unhold(std::optional<double> unhold_after_s) {
    run_.reset();  // a run before this one has ended: its journal is closed before this one's opens
    timeline_ = {};
    Outcome o;
    bool unheld = false;
    std::optional<double> arrived_t;
    const auto r = run_with(
        [](double, runtime::CellRun& run) {
          if (!in_traverse_past(run, 40.0)) return false;
          run.request(Command::hold);
          return true;
        },
        [&](double t, runtime::CellRun& run) {
          const auto* scu = run.emulators()->scu();
          const auto& x = scu->actuator(1);
          const auto& z = scu->actuator(2);
          const State state = run.supervisor().state();
          o.held = o.held || state == State::held;
          if (!unheld) {
            const double since = t - *timeline_.cause_t;
            const bool due = unhold_after_s ? since >= *unhold_after_s : state == State::held;
            if (due) {
              EXPECT_EQ(state, unhold_after_s ? State::holding : State::held);
              run.request(Command::unhold);
              unheld = true;
            }
          }
          if (arrived_t) return;
          if (x.true_position_mm() < 110.0) o.slowest_x_mm_s = std::min(o.slowest_x_mm_s, x.velocity_mm_s());
          const bool x_there = std::abs(x.true_position_mm() - 120.0) <= 0.1 && !x.moving();
          const bool z_there = std::abs(z.true_position_mm() - 60.0) <= 0.1 && !z.moving();
          if (x_there && z_there) arrived_t = t;
        });
    EXPECT_EQ(r.final_state, State::complete) << r.failure << "\n" << r.summary_text;
    EXPECT_TRUE(events("fault").empty()) << r.summary_text;
    EXPECT_TRUE(arrived_t) << "the traverse never arrived";
    if (arrived_t) o.arrived_s = *arrived_t - *timeline_.cause_t;
    return o;
  }
};

TEST_F(UnholdFromMotion, ReachesTheTargetSoonerThanStopAndReplan) {
  const Outcome resumed = hold_and_unhold(0.05);
  const Outcome replanned = hold_and_unhold(std::nullopt);
  std::cout << "  hold at x 40 mm, then to x 120 / z 60: unhold 50 ms into the hold (moving) arrives "
            << resumed.arrived_s << " s after the hold, x never below " << resumed.slowest_x_mm_s
            << " mm/s; stop (Held) and re-plan arrives " << replanned.arrived_s << " s after it\n";
  EXPECT_FALSE(resumed.held) << "resumed from the moving state, not from Held";
  EXPECT_GT(resumed.slowest_x_mm_s, 4.0) << "x never braked to rest";
  EXPECT_TRUE(replanned.held);
  // The stop costs the rest of the brake, Held's wait for the SCU's report, and the ramp up again.
  EXPECT_LT(resumed.arrived_s + 0.2, replanned.arrived_s);
}

}  // namespace
}  // namespace cellctl::testing

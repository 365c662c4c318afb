// The operator's commands in the middle of a recipe, in virtual time on the whole emulated cell:
// hold and unhold, stop and reset, and the reset that the monitor refuses while a cause is present.

#include <algorithm>
#include <array>
#include <string>

#include "encoder/diagnosis.hpp"
#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

using supervisor::Command;
using supervisor::State;

class OperatorCommands : public FaultRun {
 protected:
  void SetUp() override {
    FaultRun::SetUp();
    load_recipe_text(kTraverseRecipe);
  }

  // While Held: the largest distance either actuator moved from where it was when Held was entered.
  void track_held(double t, runtime::CellRun& run) {
    if (run.supervisor().state() != State::held) return;
    auto* scu = run.emulators()->scu();
    if (!held_at_) {
      held_at_ = t;
      held_mm_ = {scu->actuator(1).true_position_mm(), scu->actuator(2).true_position_mm()};
    }
    drift_mm_ = std::max({drift_mm_, std::abs(scu->actuator(1).true_position_mm() - held_mm_[0]),
                          std::abs(scu->actuator(2).true_position_mm() - held_mm_[1])});
  }
  [[nodiscard]] bool held_for(double t, double s) const { return held_at_ && t - *held_at_ >= s; }

  // The recipe ran to its end: Complete, both axes parked at 5 mm within the recipe's 0.1 mm.
  void expect_completed(const runtime::RunResult& r) {
    EXPECT_EQ(r.final_state, State::complete) << r.failure << "\n" << r.summary_text;
    EXPECT_EQ(outcome(), "complete");
    EXPECT_EQ(events("step_done").size(), 4u);
    EXPECT_NEAR(run_->state().axes[0].encoder_mm, 5.0, 0.1);
    EXPECT_NEAR(run_->state().axes[1].scu_mm, 5.0, 0.1);
    expect_cell_at_rest();
  }

  std::optional<double> held_at_;
  std::array<double, 2> held_mm_{};
  double drift_mm_ = 0.0;
};

TEST_F(OperatorCommands, HoldStopsTheAxesAndUnholdFinishesTheRecipe) {
  const auto r = run_with(
      [](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        run.request(Command::hold);
        return true;
      },
      [this](double t, runtime::CellRun& run) {
        track_held(t, run);
        if (held_for(t, 1.0) && run.supervisor().state() == State::held) run.request(Command::unhold);
      });
  ASSERT_TRUE(held_at_) << r.summary_text;
  const double hold_t = *timeline_.cause_t;
  EXPECT_LE(entered("Holding") - hold_t, 0.0015) << "the hold is taken in the next cycle";
  // Held once the SCU reports both axes still: the 10 mm/s ramp (0.25 s) and an RC reply (130 ms).
  std::cout << "  hold → Held after " << (*held_at_ - hold_t) * 1000.0 << " ms, drift while held "
            << drift_mm_ << " mm\n";
  EXPECT_LE(*held_at_ - hold_t, 0.25 + 0.13 + 0.05);
  EXPECT_LE(drift_mm_, 1e-6) << "the axes stay put while held";
  EXPECT_GT(entered("Unholding"), *held_at_);
  EXPECT_TRUE(events("fault").empty());
  expect_completed(r);
}

TEST_F(OperatorCommands, StopEndsStoppedAndResetGoesBackToIdle) {
  std::optional<double> stopped_at;
  const auto r = run_with(
      [](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        run.request(Command::stop);
        return true;
      },
      [&](double t, runtime::CellRun& run) {
        // The cell is closing down after Stopped; a reset in that moment returns the sequencer to Idle.
        if (run.supervisor().state() == State::stopped && !stopped_at) {
          stopped_at = t;
          run.request(Command::reset);
        }
      });
  ASSERT_TRUE(stopped_at) << r.summary_text;
  EXPECT_LE(entered("Stopping") - *timeline_.cause_t, 0.0015);
  // Controlled stop: the spindle's 400 Hz run-down at 400 Hz/s dominates.
  std::cout << "  stop → Stopped after " << (*stopped_at - *timeline_.cause_t) * 1000.0 << " ms\n";
  EXPECT_LE(*stopped_at - *timeline_.cause_t, 1.5);
  EXPECT_EQ(outcome(), "stopped");
  EXPECT_GT(entered("Resetting"), 0.0);
  EXPECT_GE(entered("Idle"), entered("Resetting"));
  EXPECT_EQ(r.final_state, State::idle) << r.summary_text;
  EXPECT_TRUE(events("fault").empty());
  expect_cell_at_rest();
}

TEST_F(OperatorCommands, OperatorStopNeedsResetBeforeUnhold) {
  // Ctrl-C holds the cell (category 2). Unhold is refused while the operator stop is latched; reset
  // clears it (its cause, the operator's request, is withdrawn); unhold then finishes the recipe.
  int phase = 0;
  const auto r = run_with(
      [this](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        interrupt_.store(true);
        return true;
      },
      [&](double t, runtime::CellRun& run) {
        track_held(t, run);
        if (phase == 0 && held_for(t, 0.5)) {
          run.request(Command::unhold);
          phase = 1;
        } else if (phase == 1 && held_for(t, 0.6)) {
          EXPECT_EQ(run.supervisor().state(), State::held) << "unhold must be refused while latched";
          run.request(Command::reset);
          phase = 2;
        } else if (phase == 2 && held_for(t, 0.7)) {
          run.request(Command::unhold);
          phase = 3;
        }
      });
  EXPECT_EQ(phase, 3);
  EXPECT_EQ(fault("operator_stop")["category"], 2);
  EXPECT_GT(notes_with("unhold refused"), 0u) << r.summary_text;
  EXPECT_GT(notes_with("faults reset in state Held"), 0u);
  EXPECT_LE(drift_mm_, 1e-6);
  expect_completed(r);
}

TEST_F(OperatorCommands, ResetIsRefusedWhileTheCauseIsPresent) {
  // Faults configured to hold (category 2); an encoder supply-voltage alarm holds the cell. A reset
  // while the alarm is on is refused; once it is off (and its diagnosis read), reset and unhold finish.
  cell_.stops.fault = config::StopCategory::controlled_hold;
  int phase = 0;
  std::optional<double> cleared_at;
  const auto r = run_with(
      [](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        run.emulators()->encoder()->set_alarm(encoder::alarm::supply_voltage, true);
        return true;
      },
      [&](double t, runtime::CellRun& run) {
        track_held(t, run);
        if (phase == 0 && held_for(t, 0.5)) {
          run.request(Command::reset);  // the alarm is still on
          phase = 1;
        } else if (phase == 1 && held_for(t, 0.6)) {
          EXPECT_TRUE(run.monitor().latch(monitor::Rule::encoder_alarm).active);
          run.emulators()->encoder()->set_alarm(encoder::alarm::supply_voltage, false);
          cleared_at = t;
          phase = 2;
        } else if (phase == 2 && t - *cleared_at > 0.2) {  // the diagnosis of the change has been read
          run.request(Command::reset);
          phase = 3;
        } else if (phase == 3 && t - *cleared_at > 0.3) {
          EXPECT_FALSE(run.monitor().any_latched());
          run.request(Command::unhold);
          phase = 4;
        }
      });
  EXPECT_EQ(phase, 4);
  EXPECT_EQ(fault("encoder_alarm")["category"], 2);
  EXPECT_GT(notes_with("reset refused: the cause of encoder_alarm is still present"), 0u) << r.summary_text;
  EXPECT_GT(notes_with("faults reset in state Held"), 0u);
  expect_completed(r);
}

TEST_F(OperatorCommands, EndedByNamesTheEmergencyStopNotACtrlCThatWasReset) {
  // Issue 22: Ctrl-C holds the cell (the shipped operator stop, category 2); the operator resets and
  // unholds; later Ctrl-C twice is an emergency stop that ends the run. The summary's ended_by names
  // that emergency stop, not the first Ctrl-C, whose latch the reset had cleared.
  int presses = 0;
  const auto r = run_with(
      [this](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 10.0)) return false;
        interrupt_.store(true);
        return true;
      },
      [&, this](double t, runtime::CellRun& run) {
        track_held(t, run);
        const auto state = run.supervisor().state();
        if (held_for(t, 0.5) && state == State::held && presses == 0) {
          run.request(Command::reset);
          presses = 1;
        } else if (presses == 1 && state == State::held && !run.monitor().demanded_stop()) {
          run.request(Command::unhold);
          presses = 2;
        } else if (presses == 2 && state == State::execute && in_traverse_past(run, 20.0)) {
          interrupt_.store(true);  // Ctrl-C again: the operator stop …
          presses = 3;
        } else if (presses == 3) {
          interrupt_.store(true);  // … and once more, the next cycle: the emergency stop
          presses = 4;
        }
      });
  ASSERT_EQ(presses, 4) << r.summary_text;
  EXPECT_EQ(r.final_state, State::aborted) << r.summary_text;
  const auto ends = events("summary");
  ASSERT_EQ(ends.size(), 1u);
  const auto ended = ends[0]["ended_by"];
  EXPECT_EQ(ended["rule"], "emergency_stop") << ended.dump();
}

}  // namespace
}  // namespace cellctl::testing

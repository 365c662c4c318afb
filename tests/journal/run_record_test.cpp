#include "journal/run_record.hpp"

#include <gtest/gtest.h>

#include "journal/event_json.hpp"
#include "journal/run_summary.hpp"

namespace cellctl::journal {
namespace {

void add(RunSummary& s, double t, const Payload& p) {
  s.add(Event{t, p});
}

TEST(RunRecord, AStepHeldKeepsItsTimeBeforeTheHoldAndAStopIncludesTheInterruptedStep) {
  RunSummary s;
  add(s, 0.0, RunStarted{"r", "c", "emulated", 3});
  add(s, 0.0, StepStarted{0, "go (line 3)"});
  add(s, 2.0, StateChanged{"Execute", "Holding", {}});
  add(s, 2.5, StateChanged{"Holding", "Held", {}});
  add(s, 6.0, StateChanged{"Held", "Unholding", {}});
  add(s, 6.0, StepStarted{0, "go (line 3)"});  // the supervisor starts the step again after the hold
  add(s, 7.0, StepEnded{0, "go (line 3)", true, {}});
  add(s, 7.0, StepStarted{1, "drill (line 5)"});
  add(s, 8.5, Command{"stop", Text::format("terminal")});
  add(s, 8.5, StateChanged{"Execute", "Stopping", {}});  // the step ends here, not when the cell is at rest
  add(s, 20.0, RunEnded{"stopped"});
  const auto& steps = s.record().steps();
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_DOUBLE_EQ(steps[0].seconds(), 7.0);
  EXPECT_DOUBLE_EQ(steps[0].held_s, 4.0);
  EXPECT_EQ(steps[1].result, "interrupted");
  EXPECT_DOUBLE_EQ(steps[1].seconds(), 1.5);
  EXPECT_TRUE(s.record().ended_by_operator());
  const auto text = s.to_text();
  EXPECT_NE(text.find("drill (line 5)  (interrupted by the stop)"), std::string::npos) << text;
  EXPECT_NE(text.find("(4.00 s of it held)"), std::string::npos) << text;
}

TEST(RunRecord, AFaultIsNotTheOperatorsStop) {
  RunSummary s;
  add(s, 0.0, RunStarted{"r", "c", "emulated", 1});
  add(s, 1.0, Fault{"operator_stop", 2, Text::format("Ctrl-C")});
  add(s, 2.0, Command{"stop", Text::format("terminal")});
  add(s, 3.0, RunEnded{"stopped"});
  EXPECT_TRUE(s.record().ended_by_operator());
  add(s, 3.0, Fault{"overspeed", 1, Text::format("x")});
  EXPECT_FALSE(s.record().ended_by_operator());
}

TEST(RunRecord, PlannedTimeOfAMoveIsItsProfileAndOfADwellItsSeconds) {
  RunRecord r;
  r.add({{"t", 0.0},
         {"event", "record"},
         {"steps",
          {{{"step", 1}, {"kind", "move"}, {"label", "m"}},
           {{"step", 2}, {"kind", "dwell"}, {"label", "d"}, {"planned_s", 0.5}}}}});
  r.add(to_json({0.0, StepStarted{0, "m"}}));
  for (int i = 0; i <= 20; ++i) {
    Sample smp;
    smp.axes = 1;
    smp.planned_mm = {static_cast<float>(std::min(i, 10))};  // the profile ends at 1.0 s
    r.add(to_json({i * 0.1, smp}));
  }
  r.add(to_json({2.0, StepEnded{0, "m", true, {}}}));
  r.add(to_json({2.0, StepStarted{1, "d"}}));
  r.add(to_json({2.6, StepEnded{1, "d", true, {}}}));
  r.finish();
  EXPECT_NEAR(*r.planned_s(r.steps()[0]), 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(*r.planned_s(r.steps()[1]), 0.5);
}

TEST(EventJson, SamplesWithoutFloatNoise) {
  Sample smp;
  smp.axes = 1;
  smp.planned_mm = {12.3f};
  smp.spindle_actual_hz = 399.7f;
  const auto line = to_json({1.27, smp}).dump();
  EXPECT_NE(line.find("[12.3]"), std::string::npos) << line;
  EXPECT_NE(line.find("399.7"), std::string::npos) << line;
  EXPECT_NE(line.find("\"t\":1.27"), std::string::npos) << line;
}

}  // namespace
}  // namespace cellctl::journal

#include "journal/run_record.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "journal/run_summary.hpp"
#include "schema/journal_line.hpp"

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
  schema::RecordHeader h;
  h.steps = {{"m", "move", std::nullopt}, {"d", "dwell", 0.5}};
  r.set_header(h);
  r.add({0.0, StepStarted{0, "m"}});
  for (int i = 0; i <= 20; ++i) {
    Sample smp;
    smp.axes = 1;
    smp.planned_mm = {static_cast<float>(std::min(i, 10))};  // the profile ends at 1.0 s
    r.add({i * 0.1, smp});
  }
  r.add({2.0, StepEnded{0, "m", true, {}}});
  r.add({2.0, StepStarted{1, "d"}});
  r.add({2.6, StepEnded{1, "d", true, {}}});
  r.finish();
  EXPECT_NEAR(*r.planned_s(r.steps()[0]), 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(*r.planned_s(r.steps()[1]), 0.5);
}

// A record of another version read back: a line of a kind this reader does not know is kept when it
// looks like a fault; a line that is no JSON object is named by file and line.
TEST(RunRecord, ReadsLinesOfKindsItDoesNotKnowAndNamesABadOne) {
  const auto dir = std::filesystem::temp_directory_path() / ("cellctl-record-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "journal.jsonl")
      << R"({"t":0.0,"event":"run_started","recipe":"r","steps":1})"
         "\n"
      << R"({"t":1.5,"event":"fault_of_a_later_kind","device":"scu","code":7})"
         "\n"
      << R"({"t":2.0,"event":"run_ended","outcome":"stopped"})"
         "\n";
  const auto r = RunRecord::load(dir);
  ASSERT_EQ(r.marks().size(), 1u);
  EXPECT_EQ(r.marks()[0].kind, MarkKind::fault);
  EXPECT_EQ(r.marks()[0].text, "code=7, scu");
  EXPECT_FALSE(r.ended_by_operator());
  std::ofstream(dir / "journal.jsonl", std::ios::app) << "[1, 2]\n";
  try {
    (void)RunRecord::load(dir);
    ADD_FAILURE() << "a bad line was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("journal.jsonl:4: not a journal line"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(JournalLine, SamplesWithoutFloatNoise) {
  Sample smp;
  smp.axes = 1;
  smp.planned_mm = {12.3f};
  smp.spindle_actual_hz = 399.7f;
  const auto line = schema::event_line({1.27, smp});
  EXPECT_NE(line.find("[12.3]"), std::string::npos) << line;
  EXPECT_NE(line.find("399.7"), std::string::npos) << line;
  EXPECT_NE(line.find("\"t\":1.27"), std::string::npos) << line;
}

}  // namespace
}  // namespace cellctl::journal

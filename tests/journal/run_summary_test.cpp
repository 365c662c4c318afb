#include "journal/run_summary.hpp"

#include <gtest/gtest.h>

namespace cellctl::journal {
namespace {

TEST(RunSummary, AddsUpRepeatedStepsAndListsFaults) {
  RunSummary s;
  s.add({0.0, RunStarted{"r", "c", "virtual-time", 4}});
  s.add({0.0, StepStarted{0, "drill 1/2 › peck in (line 19)"}});
  s.add({1.5, StepEnded{0, "drill 1/2 › peck in (line 19)", true, {}}});
  s.add({1.5, StepStarted{1, "drill 2/2 › peck in (line 19)"}});
  s.add({4.0, StepEnded{1, "drill 2/2 › peck in (line 19)", false, Text::format("timeout")}});
  s.add({4.0, Fault{"overspeed", 1, Text::format("x at {:.1f} mm/s", 30.0)}});
  s.add({5.0, RunEnded{"stopped"}});
  ASSERT_EQ(s.steps().size(), 1u);
  EXPECT_EQ(s.steps()[0].label, "drill › peck in (line 19)");
  EXPECT_EQ(s.steps()[0].count, 2);
  EXPECT_DOUBLE_EQ(s.steps()[0].seconds, 4.0);
  EXPECT_EQ(s.steps()[0].failed, 1);
  ASSERT_EQ(s.faults().size(), 1u);
  EXPECT_EQ(s.faults()[0], "4.000s overspeed (category 1): x at 30.0 mm/s");
  EXPECT_EQ(s.outcome(), "stopped");
  EXPECT_DOUBLE_EQ(s.duration_s(), 5.0);
  EXPECT_NE(s.to_text().find("(1 failed)"), std::string::npos);
}

TEST(Text, NeverOverflows) {
  const auto t = Text::format("{}", std::string(Text::kCapacity + 100, 'a'));
  EXPECT_EQ(t.view().size(), Text::kCapacity);
}

}  // namespace
}  // namespace cellctl::journal

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "journal/plot_html.hpp"
#include "journal/plot_model.hpp"
#include "journal/plot_scale.hpp"
#include "journal/plot_svg.hpp"

namespace cellctl::journal {
namespace {

TEST(NiceScale, TicksOnOneTwoFiveSteps) {
  const auto s = nice_scale(-6.5, 61.3, 8);
  EXPECT_DOUBLE_EQ(s.step, 10.0);
  EXPECT_DOUBLE_EQ(s.lo, -10.0);
  EXPECT_DOUBLE_EQ(s.hi, 70.0);
  EXPECT_EQ(s.label(s.ticks.front()), "-10");
  const auto small = nice_scale(-0.83, 0.61, 6);
  EXPECT_DOUBLE_EQ(small.step, 0.5);
  EXPECT_EQ(small.label(small.ticks[1]), "-0.5");
  EXPECT_EQ(small.label(small.ticks[2]), "0.0");  // never "-0.0"
  const auto time = nice_scale(0.0, 91.36, 14);
  EXPECT_DOUBLE_EQ(time.step, 10.0);
  EXPECT_EQ(time.label(time.ticks.back()), "100");
  const auto fine = nice_scale(0.0, 0.013, 6);
  EXPECT_DOUBLE_EQ(fine.step, 0.005);
  EXPECT_EQ(fine.label(fine.ticks[1]), "0.005");
}

TEST(NiceScale, FlatOrEmptyRangeGetsASpan) {
  const auto flat = nice_scale(400.0, 400.0, 6);
  EXPECT_LT(flat.lo, 400.0);
  EXPECT_GT(flat.hi, 400.0);
  const auto none = nice_scale(NAN, NAN, 6);
  EXPECT_EQ(none.ticks.size(), 6u);
}

RunRecord two_axis_run() {
  RunRecord r;
  schema::RecordHeader h;
  h.recipe = "r";
  h.recipe_file = "r.yaml";
  h.axes = {{"x", true}, {"z", false}};
  h.steps = {{"go <in> (line 3)", "move", std::nullopt}};
  r.set_header(h);
  r.add({0.0, RunStarted{"r", "c", "virtual-time", 1}});
  r.add({0.1, StepStarted{0, "go <in> (line 3)"}});
  for (int i = 0; i <= 10; ++i) {
    Sample s;
    s.axes = 2;
    s.planned_mm = {static_cast<float>(i), 5.0f};
    s.scu_mm = {static_cast<float>(i) - 0.5f, 5.0f};
    s.encoder_mm = static_cast<float>(i) - 0.25f;
    r.add({0.1 + i * 0.1, s});
  }
  r.add({0.6, Fault{"overspeed", 1, Text::format("x at 30 mm/s")}});
  r.add({0.7, InjectedFault{"scu", "silent", "scu:silent@0.7", "reply lost", false, false}});
  r.add({0.8, Command{"hold", Text::format("terminal")}});
  r.add({1.1, StepEnded{0, "go <in> (line 3)", true, {}}});
  r.add({1.2, RunEnded{"complete"}});
  r.finish();
  return r;
}

TEST(PlotModel, NamesAxesMeasuresFollowingErrorAndMarksFaultsInjectionsAndCommands) {
  const auto run = two_axis_run();
  const auto m = plot_model({&run});
  ASSERT_EQ(m.panels.size(), 3u);
  EXPECT_EQ(m.panels[0].series[0].name, "x planned");
  EXPECT_EQ(m.panels[0].series[2].name, "x encoder");
  EXPECT_EQ(m.panels[0].series[3].name, "z planned");
  EXPECT_EQ(m.panels[1].series[0].name, "x planned − encoder");
  EXPECT_EQ(m.panels[1].series[1].name, "z planned − SCU");
  EXPECT_NEAR(m.panels[1].series[0].v[3], 0.25, 1e-6);  // against the encoder, x measures
  ASSERT_EQ(m.marks.size(), 3u);
  EXPECT_EQ(m.marks[0].kind, "fault");
  EXPECT_EQ(m.marks[1].kind, "injected fault");
  EXPECT_NE(m.marks[1].text.find("reply lost"), std::string::npos);
  EXPECT_EQ(m.marks[2].kind, "command");
  ASSERT_EQ(m.steps.size(), 1u);
  EXPECT_EQ(m.steps[0].name, "go <in>");
}

TEST(PlotModel, FollowingErrorOnlyDuringMoves) {
  RunRecord r;
  Sample s;
  s.axes = 1;
  s.planned_mm = {0.0f};
  s.scu_mm = {40.0f};  // before any move the plan is not the axis's
  r.add({0.0, s});
  r.add({0.1, StepStarted{0, "move"}});
  r.add({0.2, s});
  r.add({0.3, StepEnded{0, "move", true, {}}});
  r.finish();
  const auto err = following_error(r, 0);
  ASSERT_EQ(err.size(), 2u);
  EXPECT_TRUE(std::isnan(err[0]));
  EXPECT_DOUBLE_EQ(err[1], -40.0);
}

TEST(PlotModel, ALongRunIsDrawnByEachBucketsExtremesKeepingPeaksAndGaps) {
  // 100 000 samples (33 min at 20 ms): one spindle spike, and a move in the middle (following error
  // only there, a gap around it).
  RunRecord r;
  constexpr int kSamples = 100000;
  constexpr int kSpike = 54321;
  for (int i = 0; i < kSamples; ++i) {
    if (i == 40000) r.add({i * 0.02, StepStarted{0, "move"}});
    Sample s;
    s.axes = 1;
    s.planned_mm = {static_cast<float>(i % 7)};
    s.scu_mm = {0.0f};
    s.spindle_actual_hz = i == kSpike ? 400.0f : 10.0f;
    r.add({i * 0.02, s});
    if (i == 60000) r.add({i * 0.02, StepEnded{0, "move", true, {}}});
    // A move shorter than a bucket (25 samples each here): gap, values, gap within one bucket.
    if (i == 80005) r.add({i * 0.02, StepStarted{1, "move"}});
    if (i == 80010) r.add({i * 0.02, StepEnded{1, "move", true, {}}});
  }
  r.finish();
  const auto m = plot_model({&r});
  const auto& spindle = m.panels[2].series[1];
  ASSERT_EQ(spindle.name, "spindle actual");
  EXPECT_LE(spindle.v.size(), 12000u);
  EXPECT_DOUBLE_EQ(spindle.t.front(), 0.0);
  EXPECT_NEAR(spindle.t.back(), (kSamples - 1) * 0.02, 0.1);
  const auto peak = std::max_element(spindle.v.begin(), spindle.v.end());
  EXPECT_DOUBLE_EQ(*peak, 400.0);
  EXPECT_NEAR(spindle.t[static_cast<std::size_t>(peak - spindle.v.begin())], kSpike * 0.02, 1e-9);
  const auto& err = m.panels[1].series[0];
  EXPECT_LE(err.v.size(), 12000u);
  EXPECT_TRUE(std::isnan(err.v.front()));
  EXPECT_TRUE(std::isnan(err.v.back()));
  std::size_t values = 0;
  double highest = -1.0;
  for (const double v : err.v) {
    if (std::isnan(v)) continue;
    ++values;
    highest = std::max(highest, v);
  }
  EXPECT_GT(values, 1000u);
  EXPECT_DOUBLE_EQ(highest, 6.0);  // planned i % 7 against an SCU at 0: every bucket keeps its 6
  // The short move's values are drawn with a gap on both sides, not joined to what follows.
  std::size_t k = 0;
  while (k < err.t.size() && (std::isnan(err.v[k]) || err.t[k] < 80000 * 0.02)) ++k;
  ASSERT_LT(k, err.t.size());
  ASSERT_GT(k, 0u);
  EXPECT_NEAR(err.t[k], 80009 * 0.02, 1e-9) << "the short move's highest value";
  EXPECT_TRUE(std::isnan(err.v[k - 1])) << "a gap before the short move";
  while (k < err.t.size() && !std::isnan(err.v[k])) ++k;
  ASSERT_LT(k, err.t.size());
  EXPECT_NEAR(err.t[k], 80011 * 0.02, 1e-9) << "the gap after the short move, kept in its bucket";
}

TEST(Plots, SvgEscapesLabelsAndHtmlIsOffline) {
  const auto run = two_axis_run();
  const auto svg = render_svg({&run});
  EXPECT_NE(svg.find("go &lt;in&gt;"), std::string::npos);
  EXPECT_EQ(svg.find("go <in>"), std::string::npos);
  EXPECT_NE(svg.find(">x planned<"), std::string::npos);
  const auto html = render_html({&run});
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_NE(html.find("\"x planned\""), std::string::npos);
  EXPECT_EQ(html.find("</in>"), std::string::npos);
}

}  // namespace
}  // namespace cellctl::journal

// The safety monitor on hand-made cell states: each rule fires on its cause with its configured
// stop category, latches, and is cleared only by a reset once the cause is gone.

#include "monitor/monitor.hpp"

#include <gtest/gtest.h>

namespace cellctl::monitor {
namespace {

using namespace std::chrono_literals;

// The monitor reads the cell's core only (axes, limits, stops).
config::CellCore cell_config() {
  return config::parse_cell_core(config::YamlNode::load_string(R"(cell: t
axes:
  - {name: x, actuator: 1, function: 1, edges_per_mm: 10, min_mm: 0, max_mm: 100, max_speed_mm_s: 20, encoder: true,
     min_ferror_mm: 0.5, ferror_mm: 4}
  - {name: z, actuator: 2, function: 2, edges_per_mm: 10, min_mm: 0, max_mm: 50, max_speed_mm_s: 10}
limits: {overspeed_mm_s: 25, disagreement_mm: 2, link_silence_ms: 300, spindle_min_hz: 100, spindle_max_hz: 800,
         spindle_tolerance_hz: 5}
stops: {fault: 1, link: 0, operator: 2, following_error: 2}
)",
                                                               "cell.yaml"),
                                 "cell.yaml");
}

cell::CellState healthy() {
  cell::CellState s;
  s.axis_count = 2;
  s.axes[0] = {.present = true, .scu_mm = 10.0, .measured = true, .encoder_mm = 10.1};
  s.axes[1] = {.present = true, .scu_mm = 5.0};
  s.encoder = {.data_exchange = true, .ready = true, .mm = 10.1};
  for (auto& l : s.links) l = {.active = true, .fault = false, .silent_for = 10ms, .counts = {}};
  s.devices = {"scu", "spindle", "encoder"};
  return s;
}

class MonitorTest : public ::testing::Test {
 protected:
  config::CellCore cfg = cell_config();
  Monitor m{cfg};
  void SetUp() override { m.arm(); }

  // Evaluates `s`; expects exactly `rule` to latch, with `category`.
  void expect_only(const cell::CellState& s, Rule rule, StopCategory category, OperatorInputs in = {}) {
    const auto fresh = m.evaluate(s, in, 1.0);
    EXPECT_EQ(fresh.count(), 1u) << fresh;
    EXPECT_TRUE(fresh.test(static_cast<std::size_t>(rule))) << to_string(rule);
    EXPECT_EQ(m.demanded_stop(), category);
    EXPECT_FALSE(m.latch(rule).detail.view().empty());
  }
};

TEST_F(MonitorTest, AHealthyCellDemandsNothing) {
  EXPECT_TRUE(m.evaluate(healthy(), {}, 0.0).none());
  EXPECT_FALSE(m.demanded_stop());
}

TEST_F(MonitorTest, PositionOutsideTheCellLimits) {
  auto s = healthy();
  s.axes[1].scu_mm = 50.6;
  expect_only(s, Rule::position_limit, StopCategory::controlled_off);
  EXPECT_EQ(m.latch(Rule::position_limit).detail.view(), "axis z at 50.60 mm, outside [0, 50] mm");
}

TEST_F(MonitorTest, PositionBelowTheLowerCellLimit) {
  auto s = healthy();
  s.axes[1].scu_mm = -0.6;  // 0.1 mm past the 0.5 mm margin below min_mm 0
  expect_only(s, Rule::position_limit, StopCategory::controlled_off);
  EXPECT_EQ(m.latch(Rule::position_limit).detail.view(), "axis z at -0.60 mm, outside [0, 50] mm");
}

TEST_F(MonitorTest, PositionInsideTheMarginAtEitherEndIsNoFault) {
  auto s = healthy();
  s.axes[1].scu_mm = -0.4;
  EXPECT_TRUE(m.evaluate(s, {}, 0.0).none());
  s.axes[1].scu_mm = 50.4;
  EXPECT_TRUE(m.evaluate(s, {}, 0.0).none());
}

TEST_F(MonitorTest, TheEncoderDecidesWhereItMeasures) {
  auto s = healthy();
  s.axes[0].scu_mm = 101.0;  // the SCU's counting drifted, the encoder is the truth
  s.axes[0].encoder_mm = 99.0;
  EXPECT_FALSE(m.evaluate(s, {}, 0.0).test(static_cast<std::size_t>(Rule::position_limit)));
}

TEST_F(MonitorTest, OverspeedFromTheEncoder) {
  auto s = healthy();
  s.axes[0].encoder_mm_s = -26.0;
  expect_only(s, Rule::overspeed, StopCategory::controlled_off);
}

TEST_F(MonitorTest, ScuAndEncoderDisagree) {
  auto s = healthy();
  s.axes[0].encoder_mm = 12.5;
  expect_only(s, Rule::disagreement, StopCategory::controlled_off);
  EXPECT_EQ(m.latch(Rule::disagreement).detail.view(),
            "axis x: SCU 10.00 mm, encoder 12.50 mm (tolerance 2 mm)");
}

TEST_F(MonitorTest, DisagreementAllowanceIsTheToleranceNoMore) {
  // Just inside and just outside the 2 mm tolerance, either sign, with a fresh SCU position.
  auto s = healthy();
  s.axes[0].encoder_mm = 10.0 + 1.9;
  EXPECT_TRUE(m.evaluate(s, {}, 0.0).none());
  s.axes[0].encoder_mm = 10.0 - 1.9;
  EXPECT_TRUE(m.evaluate(s, {}, 0.0).none());
  s.axes[0].encoder_mm = 10.0 - 2.1;
  expect_only(s, Rule::disagreement, StopCategory::controlled_off);
}

TEST_F(MonitorTest, DisagreementAllowsOnlyWhatTheAxisTravelledSinceTheScuReply) {
  // 100 ms old SCU position at 10 mm/s by the encoder: 1 mm more is allowed, 3 mm in all.
  auto s = healthy();
  s.scu_position_age = 100ms;
  s.axes[0].encoder_mm_s = 10.0;
  s.axes[0].encoder_mm = 10.0 + 2.9;
  EXPECT_TRUE(m.evaluate(s, {}, 0.0).none());
  s.axes[0].encoder_mm = 10.0 + 3.2;
  expect_only(s, Rule::disagreement, StopCategory::controlled_off);
}

TEST_F(MonitorTest, EncoderRules) {
  auto s = healthy();
  s.encoder.ready = false;
  expect_only(s, Rule::encoder_not_ready, StopCategory::controlled_off);
  Monitor m2{cfg};
  m2.arm();
  s = healthy();
  s.encoder.alarm = true;
  s.encoder.limit_switch = true;
  s.encoder.diagnosis_pending = true;
  const auto fresh = m2.evaluate(s, {}, 0.0);
  EXPECT_TRUE(fresh.test(static_cast<std::size_t>(Rule::encoder_alarm)));
  EXPECT_TRUE(fresh.test(static_cast<std::size_t>(Rule::encoder_limit_switch)));
  EXPECT_TRUE(fresh.test(static_cast<std::size_t>(Rule::encoder_diagnosis)));
}

TEST_F(MonitorTest, SpindleFaultAndTemperature) {
  auto s = healthy();
  s.spindle.fault = true;
  s.spindle.fault_number = 51;
  expect_only(s, Rule::spindle_fault, StopCategory::controlled_off);
  EXPECT_EQ(m.latch(Rule::spindle_fault).detail.view(), "spindle converter fault 51");
  s = healthy();
  s.spindle.over_temperature = true;
  expect_only(s, Rule::spindle_temperature, StopCategory::controlled_off);
}

TEST_F(MonitorTest, SpindleFrequencyOutOfRange) {
  auto s = healthy();
  s.spindle.actual_hz = 806.0;
  expect_only(s, Rule::spindle_frequency, StopCategory::controlled_off);
}

TEST_F(MonitorTest, SpindleOffItsSetPointAtSpeed) {
  m.expect_spindle(true, 400.0);
  auto s = healthy();
  s.spindle.at_speed = true;
  s.spindle.actual_hz = 390.0;
  EXPECT_TRUE(m.evaluate(s, {}, 0.5).none()) << "a reading from before the set speed was reached";
  s.spindle.settled = true;
  expect_only(s, Rule::spindle_frequency, StopCategory::controlled_off);
}

TEST_F(MonitorTest, ScuErrorBitsAreNamed) {
  auto s = healthy();
  // As the SCU session types bit 22 (remote communication time-out).
  s.scu_errors = {
      .word = 1u << 21, .first_bit = 22, .first_cause = "remote communication time-out (watchdog)"};
  expect_only(s, Rule::scu_error, StopCategory::controlled_off);
  const auto detail = std::string(m.latch(Rule::scu_error).detail.view());
  EXPECT_NE(detail.find("SCU error bit 22"), std::string::npos) << detail;
}

TEST_F(MonitorTest, SilentLinkStopsImmediately) {
  auto s = healthy();
  s.links[1].silent_for = 301ms;
  expect_only(s, Rule::link_silent, StopCategory::immediate);
  EXPECT_EQ(m.latch(Rule::link_silent).detail.view(), "spindle silent for 301 ms (limit 300 ms)");
}

TEST_F(MonitorTest, OperatorAndEmergencyStops) {
  expect_only(healthy(), Rule::operator_stop, StopCategory::controlled_hold, {.stop = true});
  Monitor m2{cfg};
  (void)m2.evaluate(healthy(), {.emergency_stop = true}, 0.0);
  EXPECT_EQ(m2.demanded_stop(), StopCategory::immediate);
}

TEST_F(MonitorTest, UnarmedOnlyOperatorRulesApply) {
  Monitor cold{cfg};
  cell::CellState s;  // nothing up yet: no links, no encoder
  s.axis_count = 2;
  EXPECT_TRUE(cold.evaluate(s, {}, 0.0).none());
  EXPECT_TRUE(cold.evaluate(s, {.stop = true}, 0.0).test(static_cast<std::size_t>(Rule::operator_stop)));
}

TEST_F(MonitorTest, LatchHoldsUntilResetWithTheCauseGone) {
  auto s = healthy();
  s.axes[0].encoder_mm_s = 30.0;
  (void)m.evaluate(s, {}, 1.0);
  s.axes[0].encoder_mm_s = 0.0;
  EXPECT_TRUE(m.evaluate(s, {}, 2.0).none());
  EXPECT_TRUE(m.any_latched()) << "the cause went away, the latch did not";
  s.axes[0].encoder_mm_s = 30.0;
  EXPECT_FALSE(m.reset(s, {})) << "reset refused while the cause is present";
  EXPECT_TRUE(m.any_latched());
  s.axes[0].encoder_mm_s = 0.0;
  EXPECT_TRUE(m.reset(s, {}));
  EXPECT_FALSE(m.any_latched());
}

TEST_F(MonitorTest, StrongestCategoryWins) {
  auto s = healthy();
  s.axes[0].encoder_mm_s = 30.0;  // category 1
  s.links[0].fault = true;        // category 0
  (void)m.evaluate(s, {}, 1.0);
  EXPECT_EQ(m.demanded_stop(), StopCategory::immediate);
}

}  // namespace
}  // namespace cellctl::monitor

namespace cellctl::monitor {
namespace {

// The supervisor's plan for axis `i`: at `planned_mm`, moving at `mm_s`.
cell::Intents planned(std::size_t i, double planned_mm, double mm_s, cell::Halt halt = cell::Halt::none) {
  cell::Intents in;
  in.halt = halt;
  in.axes[i] = {.move_id = 1,
                .move = true,
                .target_mm = 50.0,
                .speed_mm_s = mm_s,
                .soft = true,
                .planned_mm = planned_mm,
                .planned_mm_s = mm_s};
  return in;
}

bool latched(const cell::CellState& s, Monitor& m) {
  return m.evaluate(s, {}, 1.0).test(static_cast<std::size_t>(Rule::following_error));
}

// x: max 20 mm/s, min_ferror 0.5 mm, ferror 4 mm → 2 mm allowed at 10 mm/s, 0.5 mm at rest.
TEST_F(MonitorTest, FollowingErrorAllowanceGrowsWithThePlannedSpeed) {
  const auto s = healthy();  // x measured by the encoder at 10.1 mm
  m.expect_axes(planned(0, 12.0, 10.0));
  EXPECT_FALSE(latched(s, m)) << "1.9 mm behind at 10 mm/s is within 2 mm";
  m.expect_axes(planned(0, 12.2, 10.0));
  expect_only(s, Rule::following_error, StopCategory::controlled_hold);  // stops.following_error: 2
  const auto detail = std::string(m.latch(Rule::following_error).detail.view());
  EXPECT_NE(detail.find("following error 2.10 mm > 2.00 mm allowed at 10.0 mm/s"), std::string::npos)
      << detail;
}

TEST_F(MonitorTest, FollowingErrorAtRestIsHeldToTheMinimum) {
  const auto s = healthy();
  m.expect_axes(planned(0, 10.5, 0.0));
  EXPECT_FALSE(latched(s, m)) << "0.4 mm off at rest is within min_ferror 0.5 mm";
  m.expect_axes(planned(0, 9.5, 0.0));
  EXPECT_TRUE(latched(s, m)) << "0.6 mm ahead of the measurement at rest";
}

TEST_F(MonitorTest, FollowingErrorNeverExceedsFerror) {
  const auto s = healthy();
  m.expect_axes(planned(0, 10.1 + 4.1, 40.0));  // a planned speed above the axis's maximum
  EXPECT_TRUE(latched(s, m)) << "the allowance stops growing at ferror_mm";
}

TEST_F(MonitorTest, FollowingErrorOnlyWhileAMoveRunsUnhalted) {
  const auto s = healthy();
  m.expect_axes(planned(0, 20.0, 10.0, cell::Halt::controlled));
  EXPECT_FALSE(latched(s, m)) << "a halting axis leaves its plan on its own ramp";
  auto idle = planned(0, 20.0, 10.0);
  idle.axes[0].move = false;
  m.expect_axes(idle);
  EXPECT_FALSE(latched(s, m)) << "no move, no plan to follow";
}

TEST_F(MonitorTest, FollowingErrorLatchesUntilResetWithTheCauseGone) {
  const auto s = healthy();
  m.expect_axes(planned(0, 15.0, 10.0));
  EXPECT_TRUE(latched(s, m));
  m.expect_axes(planned(0, 10.1, 10.0));  // back on its plan
  (void)m.evaluate(s, {}, 2.0);
  EXPECT_TRUE(m.latch(Rule::following_error).active) << "latched until an operator reset";
  EXPECT_TRUE(m.reset(s, {}));
  EXPECT_FALSE(m.latch(Rule::following_error).active);
}

TEST_F(MonitorTest, FollowingErrorOfAnAxisKnownByTheScuAllowsForItsPositionsAge) {
  auto s = healthy();  // z: by the SCU at 5.0 mm; defaults min_ferror 1 mm, ferror 5 mm, max 10 mm/s
  s.scu_position_age = 100ms;
  m.expect_axes(planned(1, 5.0 + 5.0 + 0.9, 10.0));
  EXPECT_FALSE(latched(s, m)) << "5 mm allowed at 10 mm/s, plus 1 mm the plan moved since the reply";
  s.scu_position_age = 0ms;
  EXPECT_TRUE(latched(s, m)) << "a fresh position leaves no allowance";
}

}  // namespace
}  // namespace cellctl::monitor

// The supervisor on a protocol-free cell (plant models driven by the intents): the PackML states,
// closed-loop moves on the encoder, no-motion detection, hold/unhold, stop/reset and the monitor's
// override — deterministic, on a virtual 1 ms cycle.

#include "supervisor/supervisor.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fake_cell.hpp"
#include "recipe/recipe_loader.hpp"
#include "routines/home_record.hpp"

namespace cellctl::supervisor {
namespace {

using namespace std::chrono_literals;
using config::StopCategory;

class Recorder final : public journal::EventSink {
 public:
  void post(double t, const journal::Payload& p) noexcept override { events.push_back({t, p}); }
  template <class T>
  std::vector<std::pair<double, T>> all() const {
    std::vector<std::pair<double, T>> out;
    for (const auto& e : events)
      if (const auto* v = std::get_if<T>(&e.payload)) out.emplace_back(e.t, *v);
    return out;
  }
  std::vector<journal::Event> events;
};

const char* kCell = R"(cell: t
axes:
  - {name: x, actuator: 1, function: 1, edges_per_mm: 10, min_mm: 0, max_mm: 190, max_speed_mm_s: 20,
     min_speed_mm_s: 0.8, max_accel_mm_s2: 40, max_jerk_mm_s3: 400, encoder: true,
     homing: {strategy: end_position, speed_mm_s: 10, preset_mm: 0, home_mm: 5}}
  - {name: z, actuator: 2, function: 2, edges_per_mm: 10, min_mm: 0, max_mm: 140, max_speed_mm_s: 15,
     min_speed_mm_s: 0.8, max_accel_mm_s2: 30, max_jerk_mm_s3: 300,
     homing: {strategy: scu_initialised, sequence: 1, speed_mm_s: 10, home_mm: 5}}
encoder: {mm_per_revolution: 4, time_base: steps_per_10ms}
limits: {spindle_min_hz: 100, spindle_max_hz: 800}
)";

const std::string kRecipeHead = R"(recipe: {name: r, version: "1", cell: t}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
    z: {min_mm: 0, max_mm: 120, max_speed_mm_s: 12, tolerance_mm: 0.1}
  spindle: {min_hz: 200, max_hz: 600}
  timeouts: {move_s: 30, spindle_s: 10}
steps:
)";

class SupervisorTest : public ::testing::Test {
 protected:
  void load(const std::string& steps, double scale_error = 0.0, double plant_min_speed = 0.5,
            SupervisorSettings settings = {}) {
    cell_ = config::parse_cell_config(config::YamlNode::load_string(kCell, "cell.yaml"), "cell.yaml");
    recipe_ = recipe::parse_recipe(config::YamlNode::load_string(kRecipeHead + steps, "r.yaml"), cell_);
    program_ = recipe::unroll(recipe_);
    fake_ = std::make_unique<testing::FakeCell>(cell_, scale_error, plant_min_speed);
    sup_ = std::make_unique<Supervisor>(cell_, recipe_, program_, rec_, 0.001, settings);
  }

  // Steps the cell until `until` holds or `limit` seconds pass; returns whether it held.
  template <class Until>
  bool run(double limit, Until until, std::optional<StopCategory> demanded = std::nullopt) {
    for (int i = 0; i < static_cast<int>(limit * 1000); ++i) {
      const auto s = fake_->state(link::TimePoint{} + std::chrono::milliseconds(ms_));
      sup_->step(s, demanded, ms_ / 1000.0);
      fake_->apply(sup_->intents());
      fake_->advance(1ms);
      ++ms_;
      if (until()) return true;
    }
    return false;
  }
  bool run_to(State s, double limit = 120.0) {
    return run(limit, [&] { return sup_->state() == s; });
  }
  double t() const { return ms_ / 1000.0; }
  cell::CellState now() const { return fake_->state(link::TimePoint{} + std::chrono::milliseconds(ms_)); }

  config::CellConfig cell_;
  recipe::Recipe recipe_;
  recipe::Program program_;
  Recorder rec_;
  std::unique_ptr<testing::FakeCell> fake_;
  std::unique_ptr<Supervisor> sup_;
  int ms_ = 0;
};

TEST_F(SupervisorTest, RunsARecipeToComplete) {
  load(R"(  - home: [x, z]
  - require: {encoder_ready: true, spindle_at_rest: true, homed: [x, z]}
  - move: {to: {x: 30, z: 20}, speed_mm_s: 12}
  - spindle: {start_hz: 400}
  - repeat: {times: 2, steps: [{move: {to: {z: 60}, speed_mm_s: 6}}, {dwell: 0.5}, {move: {to: {z: 20}, speed_mm_s: 12}}]}
  - spindle: stop
)");
  EXPECT_EQ(sup_->state(), State::idle);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::complete)) << to_string(sup_->state()) << " " << sup_->failure().view();
  const auto s = now();
  EXPECT_NEAR(s.axes[0].encoder_mm, 30.0, 0.1);
  EXPECT_NEAR(s.axes[1].scu_mm, 20.0, 0.1);
  EXPECT_TRUE(s.spindle.at_rest);
  EXPECT_EQ(rec_.all<journal::StepEnded>().size(), program_.instructions.size());
  for (const auto& [time, e] : rec_.all<journal::StepEnded>()) EXPECT_TRUE(e.ok) << e.label;
  const auto ends = rec_.all<journal::RunEnded>();
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].second.outcome, "complete");
  const auto samples = rec_.all<journal::Sample>();
  ASSERT_FALSE(samples.empty());
  // The record's last sample is the cell as the run ended: taken when it did, the spindle at rest.
  EXPECT_GE(samples.back().first, ends[0].first);
  EXPECT_EQ(samples.back().second.spindle_actual_hz, 0.0f);
  EXPECT_NEAR(samples.back().second.scu_mm[1], 20.0f, 0.1f);
}

TEST_F(SupervisorTest, CoordinatedAxesArriveTogether) {
  load("  - move: {to: {x: 100, z: 25}, speed_mm_s: 12}\n");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  double x_done = -1, z_done = -1;
  ASSERT_TRUE(run(60.0, [&] {
    const auto s = now();
    if (x_done < 0 && std::abs(s.axes[0].encoder_mm - 100.0) < 0.1) x_done = t();
    if (z_done < 0 && std::abs(s.axes[1].scu_mm - 25.0) < 0.1) z_done = t();
    return sup_->state() == State::complete;
  }));
  // x travels 4× as far as z: at 12 and 3 mm/s they take the same time, give or take the ramps.
  EXPECT_NEAR(x_done, z_done, 0.6) << "x " << x_done << " s, z " << z_done << " s";
}

TEST_F(SupervisorTest, ClosedLoopCorrectsAOnePercentScaleError) {
  load("  - move: {to: {x: 120}, speed_mm_s: 15}\n", 0.01);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::complete)) << sup_->failure().view();
  EXPECT_NEAR(now().axes[0].encoder_mm, 120.0, 0.1);
  EXPECT_GE(sup_->corrections(), 1);
}

TEST_F(SupervisorTest, WithoutCorrectionTheOpenLoopMoveMissesTheTolerance) {
  SupervisorSettings open_loop;
  open_loop.move.max_corrections = 0;
  load("  - move: {to: {x: 120}, speed_mm_s: 15}\n", 0.01, 0.5, open_loop);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped));
  EXPECT_NEAR(now().axes[0].encoder_mm, 120.0 / 1.01, 0.01) << "1 % short: 1.19 mm, far outside 0.1 mm";
  EXPECT_NE(std::string(sup_->failure().view()).find("after 0 corrections"), std::string::npos)
      << sup_->failure().view();
}

TEST_F(SupervisorTest, AMoveThatProducesNoMotionIsReported) {
  // The plant's actuator needs 2 mm/s to move at all; the cell config believes 0.8 mm/s suffices.
  load("  - move: {to: {z: 50}, speed_mm_s: 1}\n", 0.0, 2.0);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 10.0));
  const std::string why(sup_->failure().view());
  EXPECT_NE(why.find("no motion: axis z stayed at 0.00 mm"), std::string::npos) << why;
  EXPECT_LT(t(), 3.0) << "detected within the no-motion time, not at the move time-out";
}

TEST_F(SupervisorTest, HoldStopsTheAxesAndUnholdFinishesTheMove) {
  load("  - move: {to: {x: 150}, speed_mm_s: 15}\n");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 40.0; }));
  ASSERT_TRUE(sup_->command(Command::hold, "test", t()));
  ASSERT_TRUE(run_to(State::held, 5.0));
  const double held_at = now().axes[0].encoder_mm;
  EXPECT_LT(held_at, 60.0);
  ASSERT_TRUE(run(1.0, [] { return false; }) == false);
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, held_at) << "held means still";
  ASSERT_TRUE(sup_->command(Command::unhold, "test", t()));
  ASSERT_TRUE(run_to(State::complete));
  EXPECT_NEAR(now().axes[0].encoder_mm, 150.0, 0.1);
}

// An unhold while the hold still brakes the axes: the move goes on from the moving state, never at
// rest in between, and the plan starts from the brake's velocity (no jump in the planned speed).
TEST_F(SupervisorTest, UnholdWhileHoldingResumesWithoutStopping) {
  load("  - move: {to: {x: 150, z: 75}, speed_mm_s: 12}\n");
  auto& x = fake_->actuators()[0];
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 40.0; }));
  ASSERT_TRUE(sup_->command(Command::hold, "test", t()));
  ASSERT_TRUE(run(0.1, [] { return false; }) == false);
  ASSERT_EQ(sup_->state(), State::holding);
  const double braking_at = x.velocity_mm_s();
  EXPECT_GT(braking_at, 5.0) << "still moving fast: the unhold below is from a moving hold";
  EXPECT_LT(braking_at, 12.0 - 1.0) << "and braking";
  ASSERT_TRUE(sup_->command(Command::unhold, "test", t()));
  (void)run(0.002, [] { return false; });  // Unholding, then the move's first cycle
  ASSERT_EQ(sup_->state(), State::execute);
  EXPECT_GT(sup_->intents().axes[0].planned_mm_s, 0.5 * braking_at) << "planned from the moving state";
  double slowest = braking_at;
  bool held = false;
  ASSERT_TRUE(run(30.0, [&] {
    if (x.true_position_mm() < 140.0) slowest = std::min(slowest, x.velocity_mm_s());  // before its end
    held = held || sup_->state() == State::held;
    return sup_->state() == State::complete;
  })) << sup_->failure().view();
  EXPECT_FALSE(held);
  EXPECT_GT(slowest, 0.5 * braking_at) << "never braked to rest";
  EXPECT_NEAR(now().axes[0].encoder_mm, 150.0, 0.1);
  EXPECT_NEAR(now().axes[1].scu_mm, 75.0, 0.1);
  EXPECT_TRUE(rec_.all<journal::Note>().empty()) << "a time-synchronised move needs no note";
}

// `path: line` asks for a straight line; resumed from a moving hold the axes' brakes (each at its own
// ramp) have left it, so the plan is time-synchronised instead, and the journal says so.
TEST_F(SupervisorTest, ALineResumedOffTheLineIsTimeSynchronisedWithANote) {
  load("  - move: {to: {x: 150, z: 75}, speed_mm_s: 12, path: line}\n");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 40.0; }));
  EXPECT_TRUE(rec_.all<journal::Note>().empty()) << "from rest the line is possible";
  ASSERT_TRUE(sup_->command(Command::hold, "test", t()));
  (void)run(0.1, [] { return false; });
  ASSERT_TRUE(sup_->command(Command::unhold, "test", t()));
  ASSERT_TRUE(run_to(State::complete)) << sup_->failure().view();
  std::string text;  // one note, posted in parts (journal::NoteWriter)
  int notes = 0;
  for (const auto& [time, note] : rec_.all<journal::Note>()) {
    text += note.text.view();
    notes += note.continued ? 0 : 1;
  }
  EXPECT_EQ(notes, 1) << text;
  EXPECT_NE(text.find("step 1: phase synchronisation impossible"), std::string::npos) << text;
}

// The SCU's motion bit comes with its RC reply, up to a keep-alive (100 ms) after a move went out: a
// hold or stop in that gap must not take the not-yet-reported motion for rest.
class MotionBitLag : public SupervisorTest, public ::testing::WithParamInterface<Command> {};

TEST_P(MotionBitLag, AHaltBeforeTheMotionIsReportedStillEndsAtRest) {
  load("  - move: {to: {x: 150}, speed_mm_s: 15}\n");
  fake_->set_motion_latency(100ms);
  auto& x = fake_->actuators()[0];
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(5.0, [&] { return x.active(); })) << "the move was commanded";
  ASSERT_TRUE(run(0.5, [&] { return x.velocity_mm_s() > 1.0; }));
  ASSERT_TRUE(x.moving());
  ASSERT_FALSE(now().axes[0].moving) << "the SCU has not reported the motion yet";

  const Command halt = GetParam();
  const State rest = halt == Command::hold ? State::held : State::stopped;
  ASSERT_TRUE(sup_->command(halt, "operator", t()));
  ASSERT_TRUE(run_to(rest, 5.0)) << to_string(sup_->state());
  EXPECT_FALSE(x.moving()) << to_string(rest) << " reached while the axis still moves at "
                           << x.velocity_mm_s() << " mm/s";
  const double at_mm = x.true_position_mm();
  (void)run(1.0, [] { return false; });
  EXPECT_EQ(sup_->state(), rest);
  EXPECT_DOUBLE_EQ(x.true_position_mm(), at_mm) << "still means still";
}

INSTANTIATE_TEST_SUITE_P(HoldAndStop, MotionBitLag, ::testing::Values(Command::hold, Command::stop),
                         [](const ::testing::TestParamInfo<Command>& i) {
                           return i.param == Command::hold ? std::string("Hold") : std::string("Stop");
                         });

TEST_F(SupervisorTest, StopThenResetReturnsToIdle) {
  load(R"(  - spindle: {start_hz: 400}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 20.0; }));
  ASSERT_TRUE(sup_->command(Command::stop, "operator", t()));
  ASSERT_TRUE(run_to(State::stopped, 10.0));
  const auto s = now();
  EXPECT_FALSE(s.axes[0].moving);
  EXPECT_TRUE(s.spindle.at_rest);
  EXPECT_FALSE(sup_->command(Command::unhold, "operator", t()));
  EXPECT_EQ(sup_->refusal().view(),
            "unhold is not possible in state Stopped: unhold is taken only in Held or Holding");
  ASSERT_TRUE(sup_->command(Command::reset, "operator", t()));
  ASSERT_TRUE(run_to(State::idle, 1.0));
}

// A recipe that ends with the spindle on is complete only when the spindle has run down (0.5 s at the
// fake's 800 Hz/s): "complete" is a cell at rest, the next process may reach in.
TEST_F(SupervisorTest, CompleteWaitsForTheSpindleToRunDown) {
  load(R"(  - spindle: {start_hz: 400}
  - move: {to: {x: 20}, speed_mm_s: 15}
)");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::completing, 30.0));
  EXPECT_GT(std::abs(now().spindle.actual_hz), 300.0) << "the recipe left the spindle on";
  ASSERT_TRUE(run_to(State::complete, 5.0));
  EXPECT_TRUE(now().spindle.at_rest);
  EXPECT_FALSE(now().axes[0].moving);
}

TEST_F(SupervisorTest, MonitorCategoryZeroAbortsWithAnImmediateHalt) {
  load(R"(  - spindle: {start_hz: 400}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 20.0; }));
  const double v_before = std::abs(now().axes[0].encoder_mm_s);
  ASSERT_GT(v_before, 5.0);
  (void)run(
      0.002, [] { return false; }, StopCategory::immediate);
  EXPECT_EQ(sup_->state(), State::aborting);
  EXPECT_EQ(sup_->intents().halt, cell::Halt::immediate);
  EXPECT_FALSE(now().axes[0].moving) << "category 0: the axis stops at once";
  ASSERT_TRUE(run_to(State::aborted, 5.0));
}

TEST_F(SupervisorTest, MonitorCategoryTwoHolds) {
  load("  - move: {to: {x: 150}, speed_mm_s: 15}\n");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 20.0; }));
  ASSERT_TRUE(run(
      5.0, [&] { return sup_->state() == State::held; }, StopCategory::controlled_hold));
  ASSERT_TRUE(sup_->command(Command::unhold, "operator", t()));
  (void)run(
      0.002, [] { return false; }, StopCategory::controlled_hold);
  EXPECT_EQ(sup_->state(), State::held) << "unhold refused while the latch demands a stop";
}

TEST_F(SupervisorTest, AFailedRequireStopsBeforeAnyMotion) {
  load(R"(  - require: {spindle_at_rest: true}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  fake_->apply([] {
    cell::Intents i;
    i.spindle.run = true;
    i.spindle.frequency_hz = 300;
    return i;
  }());
  fake_->advance(100ms);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 5.0));
  EXPECT_NE(std::string(sup_->failure().view()).find("the spindle is not at rest"), std::string::npos);
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
}

// The failure branches: each stops the run with a reason that says what to do, before or without motion.

TEST_F(SupervisorTest, ARequireHomedWithoutAHomeRecordStopsBeforeAnyMotion) {
  load(R"(  - require: {homed: [x, z]}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 5.0)) << to_string(sup_->state());
  EXPECT_EQ(std::string(sup_->failure().view()), "axis x has no home record: home it first (cellctl home x)");
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
}

// A home record made by hand: x and z homed where they stand (0 mm), with this config.
routines::HomeRecord record_at_zero() {
  routines::HomeRecord r;
  r.axes[0] = {.homed = true, .strategy = config::HomingStrategy::end_position, .measured = true};
  r.axes[1] = {.homed = true, .strategy = config::HomingStrategy::scu_initialised};
  return r;
}

// Like the SCU: at power-up its actuators are not initialised, so a home record from before a power
// loss does not hold.
TEST_F(SupervisorTest, AnScuNotInitialisedSincePowerUpBreaksTheHomeRecord) {
  auto record = record_at_zero();
  SupervisorSettings settings;
  settings.home_record = &record;
  load(R"(  - require: {homed: [x, z]}
  - move: {to: {x: 150}, speed_mm_s: 15}
)",
       0.0, 0.5, settings);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 5.0)) << to_string(sup_->state());
  EXPECT_EQ(std::string(sup_->failure().view()),
            "axis x: the SCU reports actuator 1 not initialised (power loss or reset since homing): home it "
            "again");
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
}

TEST_F(SupervisorTest, ARequireWaitsForTheScuStatusBeforeJudgingHomed) {
  auto record = record_at_zero();
  SupervisorSettings settings;
  settings.home_record = &record;
  load(R"(  - require: {homed: [x, z]}
  - move: {to: {x: 10}, speed_mm_s: 15}
)",
       0.0, 0.5, settings);
  fake_->set_scu_initialised(0, true);
  fake_->set_scu_initialised(1, true);
  fake_->set_status2_after(500ms);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::complete, 30.0)) << sup_->failure().view();
  EXPECT_NEAR(now().axes[0].encoder_mm, 10.0, 0.1);
}

// Homing on the fake cell: x (sequence 0) to its retracted end, encoder preset, to 5 mm; then z
// (sequence 1), which the SCU initialises in its retracted end; the record holds both.
TEST_F(SupervisorTest, HomingRunsTheSequencesInOrderAndWritesTheRecord) {
  load(R"(  - move: {to: {x: 40, z: 30}, speed_mm_s: 12}
  - home: [z, x]
  - require: {homed: [x, z]}
)");
  fake_->set_scu_initialised(0, true);
  fake_->set_scu_initialised(1, true);
  // (Not the recipe's business: the recipe limits let it move x and z, and homing needs none.)
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  double x_homed_at = -1.0, z_left_at = -1.0;
  ASSERT_TRUE(run(120.0, [&] {
    const auto s = now();
    if (x_homed_at < 0 && sup_->homing().phase(0) == routines::HomingPhase::homed) x_homed_at = t();
    if (z_left_at < 0 && sup_->current() && std::holds_alternative<recipe::Home>(sup_->current()->action) &&
        s.axes[1].scu_mm < 29.0)
      z_left_at = t();
    return sup_->state() == State::complete;
  })) << sup_->failure().view();
  EXPECT_GT(z_left_at, x_homed_at) << "z (sequence 1) moves only once x (sequence 0) is homed";
  const auto s = now();
  EXPECT_NEAR(s.axes[0].encoder_mm, 5.0, 0.1);
  EXPECT_NEAR(s.axes[1].scu_mm, 5.0, 0.1);
  const auto& r = sup_->home_record();
  EXPECT_TRUE(r.axes[0].homed && r.axes[1].homed);
  EXPECT_TRUE(r.updated);
  EXPECT_NEAR(r.axes[0].encoder_mm, 5.0, 0.1);
}

TEST_F(SupervisorTest, AnScuStatusNeverKnownFailsTheRequireAfterItsWait) {
  load(R"(  - require: {homed: [x]}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  fake_->set_status2_after(link::Duration::max());
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 10.0)) << to_string(sup_->state());
  EXPECT_GE(t(), 3.0) << "waited its 3 s for the status";
  EXPECT_LT(t(), 3.5);
  EXPECT_NE(std::string(sup_->failure().view()).find("did not report whether the actuators are initialised"),
            std::string::npos)
      << sup_->failure().view();
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
}

TEST_F(SupervisorTest, ARefusedSpindleStartFailsTheRunNamingTheConvertersNumber) {
  load(R"(  - spindle: {start_hz: 400}
  - move: {to: {x: 150}, speed_mm_s: 15}
)");
  fake_->refuse_spindle_start(12);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 5.0)) << to_string(sup_->state());
  EXPECT_LT(t(), 1.0) << "reported at once, not after the 10 s spindle time-out";
  EXPECT_NE(std::string(sup_->failure().view()).find("refused the start (its warning/fault 12"),
            std::string::npos)
      << sup_->failure().view();
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
}

TEST_F(SupervisorTest, ARefusedMoveFailsTheRunWithTheScusReason) {
  load(R"(  - move: {to: {x: 150, z: 40}, speed_mm_s: 10}
)");
  fake_->refuse_moves(0);
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run_to(State::stopped, 5.0)) << to_string(sup_->state());
  EXPECT_LT(t(), 1.0) << "reported at once, not after the 30 s move time-out";
  EXPECT_EQ(std::string(sup_->failure().view()),
            "the SCU refused the move of axis x to 150.000 mm (PE (permission error))");
  EXPECT_DOUBLE_EQ(now().axes[0].encoder_mm, 0.0);
  EXPECT_FALSE(now().axes[1].moving) << "the other axis of the move was stopped too";
}

TEST_F(SupervisorTest, AHoldKeepsTheSpindleRunning) {
  load(R"(  - spindle: {start_hz: 400}
  - move: {to: {x: 150}, speed_mm_s: 15}
  - spindle: stop
)");
  ASSERT_TRUE(sup_->command(Command::start, "test", t()));
  ASSERT_TRUE(run(30.0, [&] { return now().axes[0].encoder_mm > 40.0; }));
  ASSERT_TRUE(sup_->command(Command::hold, "test", t()));
  ASSERT_TRUE(run_to(State::held, 5.0));
  (void)run(1.0, [] { return false; });
  EXPECT_TRUE(now().spindle.at_speed) << "category 2 holds the axes, the spindle keeps cutting speed";
  EXPECT_FALSE(now().axes[0].moving);
  ASSERT_TRUE(sup_->command(Command::unhold, "test", t()));
  ASSERT_TRUE(run_to(State::complete));
  EXPECT_TRUE(now().spindle.at_rest);
}

}  // namespace
}  // namespace cellctl::supervisor

// The guided Teach-In (issue 10, part 5) in virtual time on the shipped cell's emulators, as the job
// runs it: a program of one Teach-In step in runtime::CellRun (issue 21: one cycle for every job). End
// to end and verified; aborted by the operator and stopped by an injected fault, each leaving the encoder's
// EEPROM and parameters as they were; a start at the encoder's native zero refused before any motion;
// the manual mode with the operator's hand moves (taught and verified) and without them (restored).
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>

#include "config/cell_config.hpp"
#include "encoder/eeprom_file.hpp"
#include "run_fixture.hpp"
#include "runtime/cell_run.hpp"

namespace cellctl::testing {
namespace {

using routines::TeachInPhase;

class TeachInTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("cellctl-teach-in-") + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    cell_ = config::load_cell_config(source_dir() / "config/cell.yaml");
    setup_ = emulation::load_emulator_setup(cell_);
    setup_.encoder->state_file = dir_ / "encoder.eeprom";  // this test's own EEPROM
    request_.axis = 0;
    request_.distance_mm = 100.0;
    request_.from_mm = 5.0;
    request_.speed_mm_s = 10.0;
  }
  void TearDown() override {
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }
  runtime::CellRun& make_run(std::vector<runtime::FaultSpec> faults = {}) {
    runtime::RunOptions o;
    o.mode = runtime::RunMode::virtual_time;
    o.emulators = setup_;
    o.journal_dir = dir_ / "journal";
    o.state_dir = dir_ / "state";
    o.faults = std::move(faults);
    recipe_ = {};
    recipe_.name = "teach-in";
    recipe_.cell = cell_.name;
    recipe_.limits.axes.resize(cell_.axes.size());
    recipe_.steps.push_back({"teach-in x", 1, request_});
    run_ = std::make_unique<runtime::CellRun>(cell_, recipe_, o);
    return *run_;
  }
  // Runs it; how its Teach-In ended.
  runtime::TeachInOutcome teach(runtime::CellRun& run) {
    result_ = run.run(interrupt_);
    EXPECT_TRUE(result_.teach_in.has_value()) << "no Teach-In step ran";
    return result_.teach_in.value_or(runtime::TeachInOutcome{});
  }
  static routines::TeachInPhase phase(const runtime::CellRun& r) {
    const auto* t = r.supervisor().teach_in();
    return t ? t->phase() : TeachInPhase::checking;
  }
  static std::string prompt(const runtime::CellRun& r) {
    const auto* t = r.supervisor().teach_in();
    return t ? std::string(t->prompt().view()) : std::string();
  }
  // The encoder's state as it was and as it must be after a failed Teach-In: its EEPROM and the
  // parameters it was last given.
  void expect_encoder_as_configured() {
    EXPECT_EQ(encoder::load_eeprom(dir_ / "encoder.eeprom"), encoder::NonVolatile{});
    EXPECT_EQ(run_->emulators()->encoder()->device().parameters(), cell_.encoder->session.parameters);
  }

  std::filesystem::path dir_;
  config::CellConfig cell_;
  emulation::EmulatorSetup setup_;
  routines::TeachInRequest request_;
  recipe::Recipe recipe_;
  std::unique_ptr<runtime::CellRun> run_;
  runtime::RunResult result_;
  std::atomic<bool> interrupt_{false};
};

TEST_F(TeachInTest, TeachesVerifiesAndGivesTheTotalResolution) {
  auto& run = make_run();
  const auto o = teach(run);
  ASSERT_TRUE(o.done) << o.failure;
  EXPECT_TRUE(o.restored);
  // 100 mm by the SCU, whose sensor reads 0.2 % long: the shaft turned 100 / 1.002 mm at 2048 steps/mm.
  // The taught unit is 1 µm: total = 100 000 × 2^25 / (travelled steps).
  const double travelled_steps = 100.0 / 1.002 * 2048.0;
  EXPECT_NEAR(o.result.total_resolution, 100000.0 * 33554432.0 / travelled_steps, 400.0);
  EXPECT_DOUBLE_EQ(o.units_per_mm, 1000.0);
  EXPECT_NEAR(o.result.scu_distance_mm, 100.0, 0.05);
  EXPECT_NEAR(o.result.encoder_distance_mm, o.result.scu_back_mm, request_.tolerance_mm);
  EXPECT_EQ(encoder::load_eeprom(dir_ / "encoder.eeprom").taught_units, o.result.total_resolution);
  EXPECT_EQ(o.taught.parameters.measuring_units, o.result.total_resolution);
  EXPECT_EQ(o.taught.parameters.units_select, encoder::UnitsSelect::per_total_range);
  EXPECT_DOUBLE_EQ(o.taught.counts_per_mm, 1000.0);
}

TEST_F(TeachInTest, ATeachInIsARunOfTheCellWithItsSafeStopVerdictsSamplesAndPlot) {
  // Issue 21: one cycle for every job. The Teach-In gets what a recipe run gets: the safe stop's
  // verdict per device, the journal's samples, the summary, the plots.
  auto& run = make_run();
  const auto o = teach(run);
  ASSERT_TRUE(o.done) << o.failure;
  EXPECT_EQ(result_.final_state, supervisor::State::complete);
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    ASSERT_TRUE(result_.safety[d].has_value()) << d;
    EXPECT_EQ(result_.safety[d]->safe, runtime::Safe::observed) << d << ": " << result_.safety[d]->evidence;
  }
  std::ifstream journal(dir_ / "journal/journal.jsonl");
  std::string line;
  int samples = 0;
  nlohmann::json summary;
  while (std::getline(journal, line)) {
    const auto j = nlohmann::json::parse(line);
    if (j.value("event", "") == "sample") ++samples;
    if (j.value("event", "") == "summary") summary = j;
  }
  // About 30 s of cell time at the config's sample period: hundreds of samples.
  EXPECT_GT(samples, 300);
  ASSERT_TRUE(summary.contains("teach_in")) << summary.dump();
  EXPECT_EQ(summary["teach_in"]["taught"], true);
  EXPECT_EQ(summary["teach_in"]["total_resolution"], o.result.total_resolution);
  EXPECT_EQ(summary["mode"], "virtual-time");
  EXPECT_TRUE(std::filesystem::exists(dir_ / "journal/plot.svg"));
}

TEST_F(TeachInTest, TeachingAgainOnAnUnchangedCellTeachesTheSameResolution) {
  // The cell as `cellctl teach-in` leaves it: the config rewritten with the taught resolution, the
  // encoder's EEPROM holding it. A second Teach-In on the same emulated plant (same shaft, same
  // SCU scale error) must find the same resolution; it once grew 0.2 % a time, because the emulated
  // shaft's lead was derived from the taught scaling instead of being the plant's.
  auto& first_run = make_run();
  const auto first = teach(first_run);
  ASSERT_TRUE(first.done) << first.failure;
  run_.reset();  // its emulators saved the EEPROM; the next run starts from it
  cell_.encoder->session = first.taught;
  auto& second_run = make_run();
  const auto second = teach(second_run);
  ASSERT_TRUE(second.done) << second.failure;
  EXPECT_NEAR(second.result.scu_distance_mm, first.result.scu_distance_mm, 0.001);
  EXPECT_NEAR(static_cast<double>(second.result.total_resolution),
              static_cast<double>(first.result.total_resolution), 1.0);
  EXPECT_EQ(encoder::load_eeprom(dir_ / "encoder.eeprom").taught_units, second.result.total_resolution);
}

TEST_F(TeachInTest, AbortDuringTheTravelRestoresTheEncoder) {
  auto& run = make_run();
  bool aborted_travelling = false;
  run.on_cycle([&](double, runtime::CellRun& r) {
    if (!aborted_travelling && phase(r) == TeachInPhase::travelling && r.state().axes[0].scu_mm > 40.0) {
      aborted_travelling = true;
      r.request(supervisor::Command::stop, "the test's operator");
    }
  });
  const auto o = teach(run);
  ASSERT_TRUE(aborted_travelling);
  EXPECT_FALSE(o.done);
  EXPECT_EQ(result_.final_state, supervisor::State::stopped);
  EXPECT_TRUE(o.restored);
  EXPECT_NE(o.failure.find("aborted by the operator in phase 'travelling'"), std::string::npos) << o.failure;
  expect_encoder_as_configured();
  EXPECT_FALSE(run.emulators()->encoder()->device().teach_in_running());
}

TEST_F(TeachInTest, AnInjectedFaultDuringTheTravelRestoresTheEncoder) {
  // The SCU reports actuator faults 20 s in (the travel from 5 mm runs from about 2 s to 13 s after the
  // start at 10 mm/s; 20 s is on the way back — both are Teach-In states the encoder must leave).
  auto spec = runtime::parse_fault_spec("scu:error@8");
  ASSERT_TRUE(std::holds_alternative<runtime::FaultSpec>(spec));
  auto& run = make_run({std::get<runtime::FaultSpec>(spec)});
  TeachInPhase phase_at_fault = TeachInPhase::checking;
  run.on_cycle([&](double t, runtime::CellRun& r) {
    if (t < 8.0) phase_at_fault = phase(r);
  });
  const auto o = teach(run);
  EXPECT_EQ(phase_at_fault, TeachInPhase::travelling);
  EXPECT_FALSE(o.done);
  EXPECT_TRUE(o.restored);
  EXPECT_NE(o.failure.find("stopped by the monitor"), std::string::npos) << o.failure;
  expect_encoder_as_configured();
}

TEST_F(TeachInTest, AFailedVerificationRestoresTheConfiguredParameters) {
  // The encoder's coupling starts to slip 2 % once the taught encoder has measured the end point: on
  // the way back it measures 0.1 mm less than the SCU (tolerance 0.05 mm).
  auto& run = make_run();
  run.on_cycle([](double, runtime::CellRun& r) {
    if (phase(r) == TeachInPhase::returning) r.emulators()->shaft()->set_slip(0.02);
  });
  const auto o = teach(run);
  EXPECT_FALSE(o.done);
  EXPECT_TRUE(o.restored);
  EXPECT_NE(o.failure.find("verification failed"), std::string::npos) << o.failure;
  EXPECT_EQ(run.emulators()->encoder()->device().parameters(), cell_.encoder->session.parameters);
}

TEST_F(TeachInTest, AStartAtTheNativeZeroIsRefusedBeforeAnyMotion) {
  // The shipped cell's axis x stands at the encoder's native zero at 0 mm.
  request_.from_mm = 0.0;
  auto& run = make_run();
  double farthest = 0.0;
  run.on_cycle([&](double, runtime::CellRun& r) { farthest = std::max(farthest, r.state().axes[0].scu_mm); });
  const auto o = teach(run);
  EXPECT_FALSE(o.done);
  EXPECT_NE(o.failure.find("native zero"), std::string::npos) << o.failure;
  // Whole, with what to do (it once ran past journal::Text's 160 octets and lost its advice).
  EXPECT_NE(o.failure.find("start at 1.0 mm or above"), std::string::npos) << o.failure;
  EXPECT_LT(farthest, 0.01) << "the axis moved although the Teach-In could not be done";
  expect_encoder_as_configured();
}

TEST_F(TeachInTest, ManualModeTeachesOverTheDistanceTheOperatorMovedAndVerifiesIt) {
  // The operator moves the rod by hand (the test pushes the emulated actuator; cellctl commands no
  // motion, as the test without a hand shows): 100 mm true travel out, confirm, back to the start
  // mark, confirm. The SCU's sensor reads 0.2 % long, so in its frame the hand travels 100.2 mm; in
  // manual mode the reference is the distance the operator was asked for, so the taught resolution
  // is that of 100 true mm.
  setup_.scu->actuators[0].physics.start_position_mm = 5.0;
  request_.manual = true;
  request_.from_mm.reset();
  auto& run = make_run();
  std::string prompts;
  std::optional<double> hand_target_mm;  // the SCU's frame, where the hand is taking the rod
  run.on_cycle([&](double, runtime::CellRun& r) {
    auto& rod = r.emulators()->scu()->actuator(1);
    if (hand_target_mm && !rod.moving()) {  // the hand has arrived: the operator confirms
      hand_target_mm.reset();
      r.confirm();
    }
    const auto p = prompt(r);
    if (p.empty() || prompts.find(p) != std::string::npos) return;
    prompts += p + "\n";
    if (p.find("by 100.000 mm in + direction") != std::string::npos) {
      hand_target_mm = 5.0 + 100.0 * 1.002;
    } else if (p.find("back to the start mark") != std::string::npos) {
      hand_target_mm = 5.0;
    } else {
      r.confirm();
      return;
    }
    rod.move_to(*hand_target_mm, 20.0, true);
  });
  const auto o = teach(run);
  ASSERT_TRUE(o.done) << o.failure << "\nprompts:\n" << prompts;
  EXPECT_TRUE(o.restored);
  EXPECT_NE(prompts.find("back to the start mark"), std::string::npos) << prompts;
  const double travelled_steps = 100.0 * 2048.0;  // 100 true mm at 2048 steps/mm
  EXPECT_NEAR(o.result.total_resolution, 100000.0 * 33554432.0 / travelled_steps, 400.0);
  EXPECT_DOUBLE_EQ(o.result.scu_distance_mm, 100.0) << "manual mode: the distance given is the reference";
  EXPECT_NEAR(o.result.encoder_distance_mm, 100.0, request_.tolerance_mm);
  EXPECT_EQ(encoder::load_eeprom(dir_ / "encoder.eeprom").taught_units, o.result.total_resolution);
  EXPECT_EQ(o.taught.parameters.measuring_units, o.result.total_resolution);
  EXPECT_NEAR(run.state().axes[0].scu_mm, 5.0, 0.05) << "the rod is back at the start mark";
}

TEST_F(TeachInTest, ManualModeGuidesTheOperatorAndAnEndWithoutTravelRestoresTheEncoder) {
  // The axis stands at 5 mm, clear of the native zero; the operator is asked to move it and confirms
  // without having moved it: the encoder has no distance to compute a resolution from.
  setup_.scu->actuators[0].physics.start_position_mm = 5.0;
  request_.manual = true;
  request_.from_mm.reset();
  auto& run = make_run();
  std::string prompts;
  run.on_cycle([&](double, runtime::CellRun& r) {
    const auto p = prompt(r);
    if (!p.empty() && prompts.find(p) == std::string::npos) {
      prompts += p + "\n";
      r.confirm();
    }
  });
  const auto o = teach(run);
  EXPECT_NE(prompts.find("Teach-In started: move axis x by 100.000 mm in + direction"), std::string::npos)
      << prompts;
  EXPECT_FALSE(o.done);
  EXPECT_TRUE(o.restored);
  EXPECT_NE(o.failure.find("Teach-In end"), std::string::npos) << o.failure;
  EXPECT_NEAR(run.state().axes[0].scu_mm, 5.0, 0.01) << "manual mode moved the axis";
  expect_encoder_as_configured();
}

}  // namespace
}  // namespace cellctl::testing

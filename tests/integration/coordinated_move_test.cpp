// Coordinated moves of two SCU actuators on the whole emulated cell in virtual time: the axes of one
// move arrive together, time-synchronised (the default) or on a line (`path: line`). Arrival is read
// from the plant (where each rod really is), not from the session: the first moment the rod is
// within the recipe's tolerance of its target and at rest. The skew between the axes must stay within
// one SCU refresh period (the keep-alive RC that refreshes every actuator's position at once; 100 ms
// in config/cell.yaml), the resolution at which the controller can see an arrival at all.

#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include "plant/actuator.hpp"
#include "run_fixture.hpp"

namespace cellctl::testing {
namespace {

class CoordinatedMove : public RunFixture {
 protected:
  struct Arrival {
    std::optional<double> x_t;
    std::optional<double> z_t;
    int x_halts = 0;  // times x came to rest before it arrived
  };

  // Runs a one-move recipe (x from x_from_mm, z from 0, to the targets) and returns when each rod
  // first stood still within the recipe's tolerance (0.1 mm) of its target.
  Arrival run_move(double x_mm, double z_mm, double speed_mm_s, const std::string& path, double x_scale_error,
                   double x_from_mm = 0.0) {
    load_recipe_text(std::string(R"(
recipe: {name: coordinated, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
    z: {min_mm: 0, max_mm: 120, max_speed_mm_s: 12, tolerance_mm: 0.1}
  timeouts: {move_s: 60}
steps:
  - {name: together, move: {to: {x: )") +
                     std::to_string(x_mm) + ", z: " + std::to_string(z_mm) +
                     "}, speed_mm_s: " + std::to_string(speed_mm_s) + path + "}}\n");
    emulators().scu->actuators[0].physics.scale_error = x_scale_error;
    emulators().scu->actuators[0].physics.start_position_mm = x_from_mm;
    auto& run = make_run();
    Arrival a;
    bool x_was_moving = false;
    run.on_cycle([&a, &x_was_moving, x_mm, z_mm](double t, runtime::CellRun& r) {
      const auto* scu = r.emulators()->scu();
      const auto arrived = [](const plant::Actuator& rod, double target_mm) {
        return std::abs(rod.true_position_mm() - target_mm) <= 0.1 && !rod.moving();
      };
      if (!a.x_t && arrived(scu->actuator(1), x_mm)) a.x_t = t;
      if (!a.x_t && x_was_moving && !scu->actuator(1).moving()) ++a.x_halts;
      x_was_moving = scu->actuator(1).moving();
      if (!a.z_t && arrived(scu->actuator(2), z_mm)) a.z_t = t;
    });
    const auto result = go();
    EXPECT_EQ(result.final_state, supervisor::State::complete) << result.failure << "\n"
                                                               << result.summary_text;
    return a;
  }

  // The SCU refresh period of the shipped cell [s].
  [[nodiscard]] double refresh_period_s() const {
    return std::chrono::duration<double>(cell_.scu->session.keepalive_period).count();
  }
};

struct MoveCase {
  double x, z, speed;
  const char* path;
};
// Ratios from 2:1 to 7.5:1 (x the longer or the shorter), each time-synchronised (without `path`, the
// default, and with `path: time`) and on a line. (At 15:1, x 150 and z 10 at 12 mm/s, z's share is
// below what its actuator runs steadily, 0.96 mm/s: the SCU runs it faster than planned and the
// following-error rule stops the run.)
constexpr MoveCase kCases[] = {{120, 60, 10, ""},
                               {120, 60, 10, ", path: line"},
                               {150, 20, 12, ", path: time"},
                               {150, 20, 12, ", path: line"},
                               {40, 100, 12, ""},
                               {40, 100, 12, ", path: line"},
                               {90, 30, 6, ", path: time"},
                               {90, 30, 6, ", path: line"}};

// The SCU's sensors read true (no scale error): the axes arrive together. One run per case.
class CoordinatedMoveCases : public CoordinatedMove, public ::testing::WithParamInterface<MoveCase> {};

TEST_P(CoordinatedMoveCases, TwoAxesArriveWithinOneScuRefreshPeriod) {
  const MoveCase c = GetParam();
  const Arrival a = run_move(c.x, c.z, c.speed, c.path, 0.0);
  ASSERT_TRUE(a.x_t && a.z_t) << "x " << c.x << " z " << c.z;
  const double skew = std::abs(*a.x_t - *a.z_t);
  std::cout << "  x 0 -> " << c.x << ", z 0 -> " << c.z << " at " << c.speed << " mm/s" << c.path
            << ": x arrives at " << *a.x_t << " s, z at " << *a.z_t << " s, skew " << skew * 1e3
            << " ms (refresh period " << refresh_period_s() * 1e3 << " ms)\n";
  EXPECT_LE(skew, refresh_period_s()) << "x " << c.x << " z " << c.z;
  EXPECT_EQ(notes_with("corrected while moving"), 0u) << "a sensor that reads true needs no correction";
}

INSTANTIATE_TEST_SUITE_P(Ratios, CoordinatedMoveCases, ::testing::ValuesIn(kCases));

// The shipped cell's x sensor reads 0.2 % long: the SCU would stop x short by that share of the
// travel. The executor learns the drift on the way and corrects x's SCU target while x still moves
// (a new target while moving: RS, RT, RE), so x arrives with z. Without that, x arrives only after a
// correction at rest (a settle time, then a short move): the skew is then that correction's time.
TEST_F(CoordinatedMove, ScaleErrorIsCorrectedWhileMovingSoBothStillArriveTogether) {
  const MoveCase c = kCases[0];
  const Arrival a = run_move(c.x, c.z, c.speed, c.path, 0.002);
  ASSERT_TRUE(a.x_t && a.z_t);
  const double skew = *a.x_t - *a.z_t;
  std::cout << "  with x reading 0.2 % long, corrected while moving: x arrives at " << *a.x_t << " s, z at "
            << *a.z_t << " s, x later by " << skew * 1e3 << " ms\n";
  EXPECT_LE(std::abs(skew), refresh_period_s());
  EXPECT_EQ(a.x_halts, 0) << "x went on to its corrected target without a stop";
  EXPECT_EQ(events("summary").at(0)["corrections"].get<int>(), 1) << "one correction, made in motion";
  EXPECT_EQ(notes_with("axis x corrected while moving: its SCU reads +0.2"), 1u);
}

// The same on the way back (x 140 → 20): the correction has the travel's sign.
TEST_F(CoordinatedMove, ScaleErrorIsCorrectedWhileMovingTowardsTheRetractedEndToo) {
  const Arrival a = run_move(20, 60, 10, "", 0.002, 140);
  ASSERT_TRUE(a.x_t && a.z_t);
  EXPECT_LE(std::abs(*a.x_t - *a.z_t), refresh_period_s());
  EXPECT_EQ(a.x_halts, 0);
  EXPECT_EQ(notes_with("axis x corrected while moving: its SCU reads +0.20 % along the travel, so its SCU "
                       "target moves by -0.2"),
            1u);
}

// An SCU that refuses an RE while the actuator still ramps down from the RS before it (the manual
// does not say it must take one): the move fails with the SCU's answer and the remedy in the config.
TEST_F(CoordinatedMove, AnScuThatRefusesTheNewTargetInMotionStopsTheRunNamingTheRemedy) {
  emulators().scu->refuses_execute_while_moving = true;
  load_recipe_text(R"(
recipe: {name: refused, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
steps:
  - {name: out, move: {to: {x: 120}, speed_mm_s: 10}}
)");
  emulators().scu->actuators[0].physics.scale_error = 0.002;
  make_run();
  const auto result = go();
  EXPECT_EQ(result.final_state, supervisor::State::stopped) << result.summary_text;
  EXPECT_NE(result.failure.find("the SCU refused axis x's corrected target while it moved (not permitted"),
            std::string::npos)
      << result.failure;
  EXPECT_NE(result.failure.find("); set its correct_in_motion: false"), std::string::npos) << result.failure;
  EXPECT_EQ(result.failure.back(), 'e') << "the whole text, not cut at the journal's 160 octets";
}

TEST_F(CoordinatedMove, ScaleErrorCorrectedOnlyAtRestDelaysTheMeasuredAxisByTheCorrection) {
  cell_.axes[0].correct_in_motion = false;
  const MoveCase c = kCases[0];
  const Arrival a = run_move(c.x, c.z, c.speed, c.path, 0.002);
  ASSERT_TRUE(a.x_t && a.z_t);
  const double skew = *a.x_t - *a.z_t;
  std::cout << "  with x reading 0.2 % long, corrected at rest: x arrives at " << *a.x_t << " s, z at "
            << *a.z_t << " s, x later by " << skew * 1e3 << " ms\n";
  EXPECT_GT(skew, refresh_period_s());
  EXPECT_LE(skew, 1.0);
  EXPECT_EQ(a.x_halts, 1) << "x stopped short, then went on by the correction";
}

}  // namespace
}  // namespace cellctl::testing

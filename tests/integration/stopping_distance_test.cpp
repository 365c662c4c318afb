// How far the axes run on after a stop is decided, per stop category, on the whole emulated cell in
// virtual time: the operator's hold (category 2), stop (1) and abort (0) in the middle of the
// traverse (x at 10 mm/s, z at 5 mm/s on the line to x 120, z 60). The bounds follow from the
// actuators' physics in config/cell.yaml and the line, not from a run:
// - a controlled stop ramps down: x 10²/(2·40 mm/s²) = 1.25 mm, z 5²/(2·30) = 0.42 mm; plus what
//   the axis travels before the RS is acted on (decided in cycle k, on the wire in k, a 38400-baud
//   telegram: well under 20 ms, 0.2 mm at 10 mm/s). At least 80 % of the ramp: it was ramped, not cut.
// - category 0 (F20, then a fast RS per axis) cuts the motion: no ramp, only that latency.
// A hold keeps the spindle turning; stop and abort run it down.

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <optional>

#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

using supervisor::Command;
using supervisor::State;

struct StopCase {
  Command command;
  const char* name;
  bool ramped;        // controlled (categories 1, 2) or cut (0)
  bool spindle_kept;  // the hold keeps it
};

void PrintTo(const StopCase& c, std::ostream* os) {
  *os << c.name;
}

constexpr double kLatencyMm = 10.0 * 0.020;  // x at 10 mm/s for 20 ms
constexpr std::array<double, 2> kRampMm{10.0 * 10.0 / (2 * 40.0), 5.0 * 5.0 / (2 * 30.0)};

class StoppingDistance : public FaultRun, public ::testing::WithParamInterface<StopCase> {
 protected:
  void SetUp() override {
    FaultRun::SetUp();
    load_recipe_text(kTraverseRecipe);
  }
};

TEST_P(StoppingDistance, StaysWithinTheCategorysBound) {
  const auto c = GetParam();
  std::array<double, 2> from{}, travel{};
  std::optional<double> at_rest_t, hz_then;
  double hz_at_cause = 0.0;
  const auto r = run_with(
      [&](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        auto* scu = run.emulators()->scu();
        from = {scu->actuator(1).true_position_mm(), scu->actuator(2).true_position_mm()};
        hz_at_cause = std::abs(run.emulators()->spindle()->motor().frequency_hz());
        run.request(c.command);
        return true;
      },
      [&](double t, runtime::CellRun& run) {
        if (!timeline_.cause_t || hz_then) return;
        auto* scu = run.emulators()->scu();
        for (std::uint8_t i = 0; i < 2; ++i)
          travel[i] = std::max(travel[i], std::abs(scu->actuator(i + 1).true_position_mm() - from[i]));
        if (!at_rest_t && !scu->actuator(1).moving() && !scu->actuator(2).moving()) at_rest_t = t;
        if (t - *timeline_.cause_t >= 0.5) {
          hz_then = std::abs(run.emulators()->spindle()->motor().frequency_hz());
          if (run.supervisor().state() == State::held) run.request(Command::stop);  // measured: end the run
        }
      });
  ASSERT_TRUE(at_rest_t) << r.summary_text;
  std::cout << "  [" << c.name << "] x ran on " << travel[0] << " mm, z " << travel[1]
            << " mm, at rest after " << (*at_rest_t - *timeline_.cause_t) * 1000.0 << " ms\n";
  for (std::size_t i = 0; i < 2; ++i) {
    const double latency_mm = kLatencyMm * (i == 0 ? 1.0 : 0.5);
    if (c.ramped) {
      EXPECT_GE(travel[i], 0.8 * kRampMm[i]) << "axis " << i << ": a controlled stop ramps down";
      EXPECT_LE(travel[i], kRampMm[i] + latency_mm) << "axis " << i;
    } else {
      EXPECT_LE(travel[i], latency_mm) << "axis " << i << ": category 0 cuts the motion";
    }
  }
  // 0.5 s after the command: a kept spindle still at its frequency, a stopped one 200 Hz into its
  // 400 Hz/s run-down (100 Hz allowed for the stop's way to the converter).
  ASSERT_TRUE(hz_then);
  if (c.spindle_kept)
    EXPECT_NEAR(*hz_then, hz_at_cause, 1.0) << "a hold keeps the spindle turning";
  else
    EXPECT_LT(*hz_then, hz_at_cause - 100.0) << "the spindle runs down";
  expect_cell_at_rest();
}

INSTANTIATE_TEST_SUITE_P(EveryCategory, StoppingDistance,
                         ::testing::Values(StopCase{Command::hold, "hold_category_2", true, true},
                                           StopCase{Command::stop, "stop_category_1", true, false},
                                           StopCase{Command::abort, "abort_category_0", false, false}),
                         [](const auto& test) { return std::string(test.param.name); });

}  // namespace
}  // namespace cellctl::testing

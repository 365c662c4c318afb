#pragma once
// Whole runs in virtual time with a cause injected on purpose: a short recipe (spindle up, a long
// coordinated traverse, back, spindle down), a cause put in place from the loop's own cycle hook,
// and the timeline of what followed — when the monitor latched which rule, when the supervisor
// began to stop, when the SCU emulator held its emergency stop, how the run ended — read from the
// journal and from the emulators, so every bound is measured from the injection, in virtual time.

#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include "run_fixture.hpp"

namespace cellctl::testing {

// Spindle to 400 Hz, then x 0 → 120 and z 0 → 60 together at 10 mm/s (about 12 s), back, spindle down.
// Every cause is injected during the traverse.
inline const std::string kTraverseRecipe =
    demo_recipe("traverse", R"(  - {name: spindle up, spindle: {start_hz: 400, direction: cw}}
  - {name: traverse, move: {to: {x: 120, z: 60}, speed_mm_s: 10}}
  - {name: back, move: {to: {x: 5, z: 5}, speed_mm_s: 12}}
  - {name: spindle down, spindle: stop}
)");
inline constexpr std::size_t kTraverseStep = 1;  // program index of the traverse

// x alone, 0 → 30 mm at 3 mm/s: below the real threshold of an actuator made to stall at 5 mm/s.
inline constexpr const char* kCreepRecipe = R"(
recipe: {name: slow, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 30}
steps:
  - {name: creep, move: {to: {x: 30}, speed_mm_s: 3}}
)";

struct Timeline {
  std::optional<double> cause_t;  // the cycle the cause was put in place (or became true in the plant)
  std::optional<double> f20_t;    // first cycle the SCU emulator held an emergency stop (F20)
};

class FaultRun : public RunFixture {
 protected:
  using Hook = std::function<bool(double t, runtime::CellRun&)>;
  using After = std::function<void(double t, runtime::CellRun&)>;

  // Runs the recipe loaded so far; `cause` is called every cycle until it returns true (the cause is
  // in place: its time is cause_t), `after` every cycle from then on.
  runtime::RunResult run_with(Hook cause, After after = {}) {
    auto& run = make_run();
    run.on_cycle([this, cause = std::move(cause), after = std::move(after)](double t, runtime::CellRun& r) {
      if (auto* scu = r.emulators()->scu(); scu && scu->emergency_stop_active() && !timeline_.f20_t)
        timeline_.f20_t = t;
      if (!timeline_.cause_t) {
        if (cause(t, r)) timeline_.cause_t = t;
        return;
      }
      if (after) after(t, r);
    });
    return go();
  }

  // True once the traverse has been running for `x_mm` of the measured axis.
  static bool in_traverse_past(const runtime::CellRun& r, double x_mm) {
    return r.supervisor().step_index() == kTraverseStep && r.state().axes[0].encoder_mm > x_mm;
  }

  // The journal's fault event for `rule` (null when there is none).
  nlohmann::json fault(const std::string& rule) const {
    for (auto& f : events("fault"))
      if (f["rule"] == rule) return f;
    return nullptr;
  }
  // When the journal first shows the supervisor entering `state` (negative: never).
  double entered(const std::string& state) const {
    for (auto& s : events("state"))
      if (s["to"] == state) return s["t"].get<double>();
    return -1.0;
  }
  std::string outcome() const {
    const auto ends = events("run_ended");
    return ends.size() == 1 ? ends[0]["outcome"].get<std::string>()
                            : std::string("(run_ended x") + std::to_string(ends.size()) + ")";
  }
  // Milliseconds from the injection to the fault event of `rule`.
  double reaction_ms(const std::string& rule) const {
    const auto f = fault(rule);
    if (f.is_null() || !timeline_.cause_t) return 1e9;
    return (f["t"].get<double>() - *timeline_.cause_t) * 1000.0;
  }

  // The plant at the end: no actuator moving, the spindle motor at 0 Hz.
  void expect_axes_at_rest() {
    auto* scu = run_->emulators()->scu();
    for (int a = 1; a <= 2; ++a) {
      EXPECT_FALSE(scu->actuator(a).moving()) << "actuator " << a;
      EXPECT_FALSE(scu->actuator(a).active()) << "actuator " << a;
    }
  }
  void expect_cell_at_rest() {
    expect_axes_at_rest();
    EXPECT_TRUE(run_->emulators()->spindle()->motor().at_rest())
        << run_->emulators()->spindle()->motor().frequency_hz() << " Hz";
  }

  // A report line per scenario, so the measured reaction times are in the test log.
  void report(const std::string& rule, double bound_ms) const {
    std::cout << "  [" << rule << "] cause at " << timeline_.cause_t.value_or(-1.0) << " s, fault after "
              << reaction_ms(rule) << " ms (bound " << bound_ms << " ms), run ended " << outcome() << "\n";
  }

  Timeline timeline_;
};

}  // namespace cellctl::testing

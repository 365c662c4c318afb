#include "cli/scu_commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "cli/commissioning.hpp"
#include "cli/confirm.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "scu/session.hpp"

namespace cellctl::cli {
namespace {

enum class ScuAction { status, move, stop };

struct ScuOptions : DeviceOptions {
  ScuOptions() { timeout_s = 60.0; }
  int function = 1;
  int actuator = 1;
  double position_mm = 0.0;
  double speed_mm_s = 5.0;
  bool fast = false;
  bool beyond_travel = false;  // a target outside the axis's travel, deliberately (confirmed)
  bool yes = false;            // confirmed beforehand (scripts)
};

// The axis the actuator moves in the cell, if it is one.
const config::AxisConfig* axis_of(const config::CellConfig& cell, int actuator) {
  for (const auto& a : cell.axes)
    if (a.actuator == actuator) return &a;
  return nullptr;
}

// Why the move may not start, before anything moves; empty when it may. The stroke is the
// actuator's physical end: never a target. The axis's travel (min_mm/max_mm, what the safety monitor
// holds a run to) only with --beyond-travel, confirmed.
std::string target_problem(const config::CellConfig& cell, const ScuOptions& o) {
  const auto& spec = cell.scu->session.specs[static_cast<std::size_t>(o.actuator - 1)];
  if (!cell.scu->session.actuators.test(static_cast<std::size_t>(o.actuator - 1)))
    return fmt::format("actuator {} is not fitted (scu.actuators in {})", o.actuator, cell.source.string());
  if (o.position_mm < 0.0 || o.position_mm > spec.stroke_mm)
    return fmt::format(
        "{:g} mm is beyond actuator {}'s stroke of 0 to {:g} mm: it would run into its end; nothing moved",
        o.position_mm, o.actuator, spec.stroke_mm);
  const auto* axis = axis_of(cell, o.actuator);
  if (axis && !o.beyond_travel && (o.position_mm < axis->min_mm || o.position_mm > axis->max_mm))
    return fmt::format(
        "{:g} mm is beyond axis {}'s travel of {:g} to {:g} mm (actuator {}; axes[].min_mm/max_mm in {}); "
        "nothing moved. To move there deliberately add --beyond-travel (it asks first)",
        o.position_mm, axis->name, axis->min_mm, axis->max_mm, o.actuator, cell.source.string());
  return {};
}

// After a move that did not arrive: what ended it, in words, and what to do.
std::string why_not_arrived(const scu::Snapshot& s, const scu::ActuatorSpec& spec, int actuator,
                            double start_mm, double target_mm) {
  const auto& a = s.actuators[static_cast<std::size_t>(actuator - 1)];
  constexpr double kAtEndMm = 0.5;  // the SCU's end stop is within this of the stroke's end
  const bool at_end_on_the_way = (a.position_mm <= kAtEndMm && target_mm < a.position_mm) ||
                                 (a.position_mm >= spec.stroke_mm - kAtEndMm && target_mm > a.position_mm);
  if (at_end_on_the_way)
    return fmt::format("it ran into its end at {:.2f} mm (stroke 0 to {:g} mm)", a.position_mm,
                       spec.stroke_mm);
  if (a.status.limit_signal) return "the actuator reports its limit signal";
  if (s.errors.any()) return "the SCU reports an error: see the error word below";
  if (std::abs(a.position_mm - start_mm) < kAtEndMm)
    return "it did not move: a speed below the actuator's minimum does not move it — try a higher "
           "--speed-mm-s";
  return fmt::format("it stopped {:.2f} mm before the target (stopped or stalled): see the status below",
                     std::abs(target_mm - a.position_mm));
}

void print_snapshot(const scu::Snapshot& s) {
  for (std::size_t i = 0; i < s.actuators.size(); ++i) {
    const auto& a = s.actuators[i];
    if (!a.configured) continue;
    const auto& st = a.status;
    fmt::print("actuator {}     {:.2f} mm ({} edges), {}{}{}{}{}\n", i + 1, a.position_mm, a.position_edges,
               !st.present        ? "NOT PRESENT"
               : st.motion_active ? "moving"
                                  : "at rest",
               st.in_position ? ", in position reached" : "", st.out_position ? ", out position reached" : "",
               st.limit_signal ? ", limit signal" : "", a.initialised ? ", initialised" : "");
  }
  if (!s.errors.any()) {
    fmt::print("errors         none\n");
  } else {
    fmt::print("errors         0x{:08x}\n", s.errors.raw());
    s.errors.for_each_cause(
        [](int bit, std::string_view cause) { fmt::print("  bit {:2}       {}\n", bit, cause); });
  }
  for (std::size_t f = 0; f < s.functions.size(); ++f) {
    const auto& fs = s.functions[f];
    if (fs.outcome == scu::MoveOutcome::none && !fs.execution_open) continue;
    fmt::print("function F{}    {}{}\n", f + 1, scu::to_string(fs.outcome),
               fs.execution_open ? " (RE open)" : "");
  }
}

class ScuCommissioning {
 public:
  ScuCommissioning(const GlobalOptions& global, const ScuOptions& options, const config::ScuSection& section)
      : options_(options),
        spec_(section.session.specs[static_cast<std::size_t>(options.actuator - 1)]),
        c_(global, options, section.port, "SCU", section.session) {}

  int run(ScuAction action) {
    c_.activate();
    if (!c_.drive([&] { return c_.session().lifecycle() == link::Lifecycle::active; }))
      return c_.failed_to("open remote mode");
    int code = kExitOk;
    switch (action) {
      case ScuAction::status:
        break;
      case ScuAction::move:
        code = move();
        break;
      case ScuAction::stop:
        if (const auto r = c_.session().stop(options_.function, !options_.fast); !r) {
          if (r.status == scu::CommandStatus::unknown_function)
            spdlog::error("F{} is not a function of this SCU: check scu.functions in the cell config",
                          options_.function);
          else
            spdlog::error("stop of F{} refused: {}", options_.function, to_string(r.status));
          code = kExitFailed;
        }
        break;
    }
    if (code == kExitOk) print_snapshot(c_.snapshot());
    return close(code);
  }

 private:
  int move() {
    const double start_mm =
        c_.snapshot().actuators[static_cast<std::size_t>(options_.actuator - 1)].position_mm;
    const scu::ActuatorTarget target[] = {{options_.actuator, options_.position_mm}};
    if (const auto r = c_.session().move_to(options_.function, target, options_.speed_mm_s, !options_.fast);
        !r) {
      using enum scu::CommandStatus;
      if (r.status == unknown_function || r.status == wrong_actuators || r.status == bad_speed)
        spdlog::error(
            "move refused: F{} must be a configured function that moves exactly actuator {} "
            "(see scu.functions in the cell config), speed above 0",
            options_.function, options_.actuator);
      else
        spdlog::error("move refused: F{}: {}", options_.function, to_string(r.status));
      return kExitFailed;
    }
    const auto& f = c_.snapshot().functions[static_cast<std::size_t>(options_.function - 1)];
    // Waits for the motion to end and its RS to be acknowledged.
    const auto& a = c_.snapshot().actuators[static_cast<std::size_t>(options_.actuator - 1)];
    const bool ended = c_.drive_showing(
        [&] {
          return f.outcome != scu::MoveOutcome::queued && f.outcome != scu::MoveOutcome::running &&
                 !f.execution_open;
        },
        [&] {
          return fmt::format("F{} {}: actuator {} at {:.2f} mm, target {:.2f} mm", options_.function,
                             f.execution_open && f.outcome != scu::MoveOutcome::queued &&
                                     f.outcome != scu::MoveOutcome::running
                                 ? "ending (RS)"
                                 : scu::to_string(f.outcome),
                             options_.actuator, a.position_mm, options_.position_mm);
        });
    if (!ended) return c_.failed_to("finish the move (raise --timeout for long strokes)");
    if (f.outcome == scu::MoveOutcome::arrived) return kExitOk;
    spdlog::error(
        "F{} {} (actuator {} at {:.2f} mm, target {:.2f} mm): {}", options_.function,
        scu::to_string(f.outcome), options_.actuator, a.position_mm, options_.position_mm,
        f.outcome == scu::MoveOutcome::refused
            ? std::string("see the error word below")
            : why_not_arrived(c_.snapshot(), spec_, options_.actuator, start_mm, options_.position_mm));
    print_snapshot(c_.snapshot());
    return kExitFailed;
  }

  // Leaves remote mode in order (RS for open REs, then RA), also after Ctrl-C.
  int close(int code) {
    bool closed = false;
    if (c_.shut_down(closed)) {
      spdlog::warn("interrupted; SCU remote mode {}",
                   closed ? "closed, motion stopped" : "NOT confirmed closed");
      return kExitInterrupted;
    }
    if (!closed && code == kExitOk) return c_.failed_to("leave remote mode");
    return code;
  }

  const ScuOptions& options_;
  scu::ActuatorSpec spec_;
  Commissioning<scu::Session> c_;
};

int run_scu(const GlobalOptions& global, const ScuOptions& options, ScuAction action) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (!cell.scu) {
    spdlog::error("{} has no scu: section; add one (port, actuators, functions)", global.config);
    return kExitConfig;
  }
  if (action == ScuAction::move) {
    if (const auto problem = target_problem(cell, options); !problem.empty()) {
      spdlog::error("scu move refused: {}", problem);
      return kExitUsage;
    }
    if (const auto* axis = axis_of(cell, options.actuator);
        axis && (options.position_mm < axis->min_mm || options.position_mm > axis->max_mm)) {
      const auto question = fmt::format(
          "Move actuator {} to {:g} mm, beyond axis {}'s travel of {:g} to {:g} mm? Nothing but the SCU's "
          "own limits holds it there. Keep clear of the cell.",
          options.actuator, options.position_mm, axis->name, axis->min_mm, axis->max_mm);
      switch (confirm(question, options.yes)) {
        case Confirmation::confirmed:
          break;
        case Confirmation::no_terminal:
          spdlog::error(
              "scu move: --beyond-travel needs a confirmation and there is no terminal to ask on: add --yes");
          return kExitUsage;
        case Confirmation::declined:
          fmt::print("not confirmed: nothing moved\n");
          return kExitFailed;
      }
    }
  }
  ScuCommissioning commissioning(global, options, *cell.scu);
  return commissioning.run(action);
}

}  // namespace

void add_scu_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<ScuOptions>();
  DeviceGroup group(app, "scu", "Commission the Ewellix SCU control unit and its actuators (RS232)", *options,
                    "Seconds to wait for the SCU or the motion");

  auto add = [&](const char* name, const char* help, ScuAction action) {
    auto* sub = group.add_action(name, help);
    commands.on(sub, [&commands, options, action] { return run_scu(commands.global, *options, action); });
    return sub;
  };
  add("status", "Print positions, actuator status and the error word", ScuAction::status);
  auto* move =
      add("move", "Move one actuator to a position in mm, wait for the end, close with RS", ScuAction::move);
  move->add_option("--function", options->function, "Function F1..F10 that moves the actuator")
      ->check(CLI::Range(1, 10))
      ->capture_default_str();
  move->add_option("--actuator", options->actuator, "Actuator 1..6")
      ->check(CLI::Range(1, 6))
      ->capture_default_str();
  move->add_option("--position-mm", options->position_mm,
                   "Target in mm (the actuator's edges_per_mm in the config converts)")
      ->required();
  move->add_option("--speed-mm-s", options->speed_mm_s,
                   "Speed in mm/s (sent as % of the actuator's full speed, at least 1 %)")
      ->check(CLI::Range(0.001, 1000.0))
      ->capture_default_str();
  move->add_flag("--fast", options->fast, "Fast start/stop (no ramps)");
  move->add_flag("--beyond-travel", options->beyond_travel,
                 "Allow a target outside the axis's travel (min_mm/max_mm), never beyond the actuator's "
                 "stroke; asks first");
  move->add_flag("--yes", options->yes, "Confirm --beyond-travel beforehand (for scripts)");
  auto* stop = add("stop", "Stop a function (soft unless --fast)", ScuAction::stop);
  stop->add_option("--function", options->function, "Function F1..F10")
      ->check(CLI::Range(1, 10))
      ->capture_default_str();
  stop->add_flag("--fast", options->fast, "Fast stop");
}

}  // namespace cellctl::cli

#include "cli/home_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/confirm.hpp"
#include "cli/run_command.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "jobs/home_job.hpp"
#include "jobs/run_record_info.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/home_record_file.hpp"

namespace cellctl::cli {
namespace {

struct HomeArgs {
  std::vector<std::string> axes;
  bool yes = false;
  RunArgs run;
};

// What homing will do with one axis, in words, for the confirmation.
std::string plan(const config::AxisConfig& a) {
  const auto& h = a.homing;
  const char* end = h.end == config::HomingEnd::retracted ? "retracted" : "extended";
  switch (h.strategy) {
    case config::HomingStrategy::absolute_encoder:
      return "absolute encoder — no motion: checks the encoder (ready, inside the travel, as last homed)";
    case config::HomingStrategy::end_position:
      return a.encoder
                 ? fmt::format(
                       "end position — MOVES into the {} end at {:g} mm/s, presets the encoder "
                       "to {:g} mm there, then MOVES to {:g} mm",
                       end, h.speed_mm_s, h.preset_mm, h.home_mm)
                 : fmt::format("end position — MOVES into the {} end at {:g} mm/s, then MOVES to {:g} mm",
                               end, h.speed_mm_s, h.home_mm);
    case config::HomingStrategy::scu_initialised:
      return fmt::format(
          "SCU initialised — if the SCU has not initialised actuator {}, MOVES into the {} "
          "end at {:g} mm/s; then MOVES to {:g} mm",
          a.actuator, end, h.speed_mm_s, h.home_mm);
    case config::HomingStrategy::none:
      break;
  }
  return "not homed";
}

int home(const GlobalOptions& global, const HomeArgs& args) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (const auto problem = run_args_problem(args.run, cell); !problem.empty()) {
    spdlog::error("{}", problem);
    return kExitUsage;
  }
  const auto chosen = jobs::homing_axes(cell, global.config, args.axes);
  if (const auto* why = std::get_if<std::string>(&chosen)) {
    spdlog::error("home: {}", *why);
    return kExitUsage;
  }
  const auto& axes = std::get<std::vector<std::size_t>>(chosen);

  const auto state_dir =
      args.run.state_dir.empty() ? cell.state_dir : std::filesystem::path(args.run.state_dir);
  const auto mode = args.run.virtual_time ? std::string_view("virtual-time")
                    : args.run.emulate    ? std::string_view("emulated")
                                          : std::string_view{};
  fmt::print("cellctl home: cell '{}', home record {}{}\n", cell.name,
             runtime::home_record_path(state_dir, mode).string(),
             mode.empty() ? "" : " (a dry run's own: the cell's home.json is left alone)");
  for (auto i : axes)
    fmt::print("  {} (sequence {}): {}\n", cell.axes[i].name, cell.axes[i].homing.sequence,
               plan(cell.axes[i]));
  fmt::print(
      "  before any motion it refuses when the spindle turns, a device is not ready or a limit is "
      "active;\n  Ctrl-C, a typed stop or a fault stops every moving axis\n");
  switch (confirm("Home now? The axes listed MOVE. Keep clear of the cell.", args.yes)) {
    case Confirmation::confirmed:
      break;
    case Confirmation::no_terminal:
      spdlog::error("home: confirmation needed and no terminal to ask on: add --yes to home from a script");
      return kExitUsage;
    case Confirmation::declined:
      fmt::print("not confirmed: nothing moved\n");
      return kExitFailed;
  }

  const auto run_dir = args.run.journal_dir.empty() ? jobs::default_run_dir("home")
                                                    : std::filesystem::path(args.run.journal_dir);
  recipe::Recipe recipe;
  try {
    recipe = jobs::write_homing_recipe(cell, axes, run_dir);
  } catch (const recipe::RecipeErrors& e) {
    for (const auto& err : e.errors()) spdlog::error("{}", err.what());
    return kExitConfig;
  } catch (const std::runtime_error& e) {
    spdlog::error("home: {}", e.what());
    return kExitFailed;
  }
  return run_loaded_recipe(global, cell, recipe, args.run, run_dir);
}

}  // namespace

void add_home_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand("home", "Home axes as the cell config's homing says (asks before motion)");
  sub->footer(
      "Without AXIS: every axis that has homing, in the order of homing.sequence (the same number: "
      "together).\n"
      "Strategies (axes[].homing.strategy): absolute_encoder (no motion), end_position (into an end, "
      "encoder\n"
      "preset there, to home_mm), scu_initialised (the SCU's own initialisation; into the retracted end "
      "when\n"
      "the SCU has not initialised the actuator, then to home_mm). Before any motion it refuses, with the\n"
      "reason, when the spindle turns, a device is not ready or a limit is active. The home record\n"
      "<state_dir>/home.json (per axis: strategy, encoder and SCU positions, time, config SHA-256) is "
      "written\n"
      "at the end; `require: {homed: [...]}` in a recipe checks it against the devices.\n"
      "While it runs: hold, unhold, stop, abort, reset as in `cellctl run`; Ctrl-C stops every moving axis.\n"
      "Exit status as `cellctl run`: 0 homed, 1 refused or failed (the reason is printed), 2 bad command "
      "line\n"
      "or no confirmation possible, 3 bad config, 4 a port could not be opened, 130 stopped by the "
      "operator.");
  auto args = std::make_shared<HomeArgs>();
  sub->add_option("axes", args->axes, "Axes to home (default: every axis with homing)");
  sub->add_flag("-y,--yes", args->yes, "Do not ask before motion (for scripts)");
  add_run_options(sub, args->run);
  commands.on(sub, [&commands, args] { return home(commands.global, *args); });
}

}  // namespace cellctl::cli

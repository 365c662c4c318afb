#include "cli/home_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/exit_codes.hpp"
#include "cli/run_command.hpp"
#include "cli/run_record_info.hpp"
#include "config/cell_config.hpp"
#include "recipe/recipe_loader.hpp"
#include "routines/home_record_file.hpp"

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

// Asks on the terminal; false unless the operator types yes.
bool confirmed() {
  fmt::print("Home now? The axes listed MOVE. Keep clear of the cell. Type yes and Enter: ");
  std::fflush(stdout);
  std::string answer;
  if (!std::getline(std::cin, answer)) return false;
  return answer == "yes" || answer == "y" || answer == "YES" || answer == "Y";
}

int home(const GlobalOptions& global, const HomeArgs& args) {
  const auto cell = config::load_cell_config(global.config);
  if (const auto problem = run_args_problem(args.run, cell); !problem.empty()) {
    spdlog::error("{}", problem);
    return kExitUsage;
  }
  std::vector<std::size_t> axes;
  for (const auto& name : args.axes) {
    const auto* a = cell.axis(name);
    if (!a) {
      spdlog::error("home: the cell has no axis '{}'", name);
      return kExitUsage;
    }
    if (a->homing.strategy == config::HomingStrategy::none) {
      spdlog::error("home: axis {} has no homing in {} (axes[].homing.strategy)", name, global.config);
      return kExitUsage;
    }
    const auto i = static_cast<std::size_t>(a - cell.axes.data());
    if (std::find(axes.begin(), axes.end(), i) == axes.end()) axes.push_back(i);
  }
  if (args.axes.empty())
    for (std::size_t i = 0; i < cell.axes.size(); ++i)
      if (cell.axes[i].homing.strategy != config::HomingStrategy::none) axes.push_back(i);
  if (axes.empty()) {
    spdlog::error("home: no axis in {} has homing (axes[].homing.strategy)", global.config);
    return kExitUsage;
  }
  std::stable_sort(axes.begin(), axes.end(), [&](std::size_t l, std::size_t r) {
    return cell.axes[l].homing.sequence < cell.axes[r].homing.sequence;
  });

  std::vector<std::string> names;
  for (auto i : axes) names.push_back(cell.axes[i].name);
  const auto state_dir =
      args.run.state_dir.empty() ? cell.state_dir : std::filesystem::path(args.run.state_dir);
  const auto mode = args.run.virtual_time ? std::string_view("virtual-time")
                    : args.run.emulate    ? std::string_view("emulated")
                                          : std::string_view{};
  fmt::print("cellctl home: cell '{}', home record {}{}\n", cell.name,
             routines::home_record_path(state_dir, mode).string(),
             mode.empty() ? "" : " (a dry run's own: the cell's home.json is left alone)");
  for (auto i : axes)
    fmt::print("  {} (sequence {}): {}\n", cell.axes[i].name, cell.axes[i].homing.sequence,
               plan(cell.axes[i]));
  fmt::print(
      "  before any motion it refuses when the spindle turns, a device is not ready or a limit is "
      "active;\n  Ctrl-C, a typed stop or a fault stops every moving axis\n");
  if (!args.yes) {
    if (isatty(STDIN_FILENO) == 0) {
      spdlog::error("home: confirmation needed and no terminal to ask on: add --yes to home from a script");
      return kExitUsage;
    }
    if (!confirmed()) {
      fmt::print("not confirmed: nothing moved\n");
      return kExitFailed;
    }
  }

  // The one-step recipe, kept with the run record: `cellctl run <dir>/home.yaml` does the same again.
  const auto run_dir =
      args.run.journal_dir.empty() ? default_run_dir("home") : std::filesystem::path(args.run.journal_dir);
  std::filesystem::create_directories(run_dir);
  const auto recipe_file = run_dir / "home.yaml";
  {
    std::ofstream out(recipe_file);
    out << fmt::format(
        "# Written by cellctl home: the homing this run record is of.\n"
        "recipe: {{name: home, version: \"1\", cell: {}, description: \"cellctl home {}\"}}\n"
        "limits: {{axes: {{}}}}\n"
        "steps:\n"
        "  - name: home {}\n"
        "    home: [{}]\n",
        cell.name, fmt::join(names, " "), fmt::join(names, ", "), fmt::join(names, ", "));
    if (!out) {
      spdlog::error("home: cannot write {}", recipe_file.string());
      return kExitFailed;
    }
  }
  recipe::Recipe recipe;
  try {
    recipe = recipe::load_recipe(recipe_file, cell);
  } catch (const recipe::RecipeErrors& e) {
    for (const auto& err : e.errors()) spdlog::error("{}", err.what());
    return kExitConfig;
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

#include "cli/run_command.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <ctime>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cli/drive.hpp"
#include "cli/exit_codes.hpp"
#include "cli/operator_console.hpp"
#include "cli/status_printer.hpp"
#include "config/cell_config.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::cli {
namespace {

struct RunArgs {
  std::string recipe;
  bool emulate = false;
  bool virtual_time = false;
  std::string journal_dir;
  std::vector<std::string> faults_text;
  std::vector<runtime::FaultSpec> faults;  // parsed (and so checked) by the option's validator
};

// --fault's validator: the text becomes a FaultSpec here, or the reason is CLI11's error (exit 2).
CLI::Validator fault_spec_validator(std::vector<runtime::FaultSpec>& out) {
  return CLI::Validator(
      [&out](std::string& text) -> std::string {
        auto parsed = runtime::parse_fault_spec(text);
        if (auto* e = std::get_if<runtime::FaultSpecError>(&parsed)) return "'" + text + "': " + e->reason;
        out.push_back(std::get<runtime::FaultSpec>(std::move(parsed)));
        return {};
      },
      "DEVICE:KIND@T[+D]");
}

std::string default_journal_dir(const recipe::Recipe& r) {
  const auto now = std::chrono::system_clock::now();
  return fmt::format("runs/{}-{:%Y%m%d-%H%M%S}", r.name,
                     fmt::localtime(std::chrono::system_clock::to_time_t(now)));
}

int run_recipe(const GlobalOptions& global, const RunArgs& args) {
  if (!args.faults.empty() && !args.emulate && !args.virtual_time) {
    spdlog::error("--fault: faults are rehearsed on emulators only: add --emulate or --virtual-time");
    return kExitUsage;
  }
  const auto cell = config::load_cell_config(global.config);
  if (auto problem = runtime::FaultRehearsal::problem(args.faults, cell)) {
    spdlog::error("{}", *problem);
    return kExitUsage;
  }
  recipe::Recipe recipe;
  try {
    recipe = recipe::load_recipe(args.recipe, cell);
  } catch (const recipe::RecipeErrors& e) {
    for (const auto& err : e.errors()) spdlog::error("{}", err.what());
    spdlog::error("{}: {} problem{}; nothing was moved", args.recipe, e.errors().size(),
                  e.errors().size() == 1 ? "" : "s");
    return kExitConfig;
  }

  runtime::RunOptions options;
  options.mode = args.virtual_time ? runtime::RunMode::virtual_time
                 : args.emulate    ? runtime::RunMode::emulated
                                   : runtime::RunMode::hardware;
  options.journal_dir = args.journal_dir.empty() ? default_journal_dir(recipe) : args.journal_dir;
  options.trace = global.trace;
  options.faults = args.faults;

  runtime::CellRun run(cell, recipe, options);
  fmt::print("cellctl: running '{}' {} on cell '{}' ({})\n", recipe.name, recipe.version, cell.name,
             to_string(options.mode));
  for (const auto& d : run.links().describe()) fmt::print("  {}\n", d);
  for (const auto& f : options.faults)
    fmt::print("  fault to rehearse: {} — {}\n", f.text, runtime::FaultRehearsal::what(f));
  fmt::print("  run record: {}/journal.jsonl, plot: {}/plot.svg\n", options.journal_dir.string(),
             options.journal_dir.string());

  runtime::RunResult result;
  {
    StatusPrinter printer(run.status(), cell);
    OperatorConsole console(run);
    if (console.active())
      fmt::print("  type hold, unhold, stop, abort or reset + Enter; Ctrl-C stops, twice aborts\n");
    result = run.run(g_interrupted, &g_terminated);
  }
  for (const auto& w : run.realtime_warnings()) spdlog::warn("real-time: {}", w);
  fmt::print("\n{}", result.summary_text);
  if (!result.failure.empty()) fmt::print("failed step: {}\n", result.failure);
  for (const auto& n : result.device_notes) fmt::print("device: {}\n", n);
  fmt::print("{} cycles; {} s of cell time in {:.2f} s", result.cycles,
             fmt::format("{:.2f}", result.duration_s), result.wall_s);
  if (options.mode == runtime::RunMode::virtual_time)
    fmt::print(" ({:.0f}× real time)", result.duration_s / result.wall_s);
  fmt::print("\n{}\n", result.loop_summary);
  fmt::print("run record: {}\n", options.journal_dir.string());

  if (result.final_state == supervisor::State::complete) return kExitOk;
  return result.interrupted ? kExitInterrupted : kExitFailed;
}

}  // namespace

void add_run_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand(
      "run", "Run a recipe on the cell (hardware, emulators on pseudo-terminals, or virtual time)");
  sub->footer(
      "Devices whose port is 'emulated' in the cell config run as emulators inside cellctl.\n"
      "Exit status: 0 complete, 1 stopped or aborted by a fault or a failed step, 2 bad command line (a bad\n"
      "--fault says why), 3 bad config or recipe "
      "(nothing moved), 4 a port could not be opened, 130 stopped by Ctrl-C.\n"
      "Ctrl-C once: operator stop (category from stops.operator; 2 holds the cell); twice: emergency stop.\n"
      "SIGTERM: a controlled stop (category 1).");
  auto args = std::make_shared<RunArgs>();
  sub->add_option("recipe", args->recipe, "Recipe file (YAML)")->required();  // unreadable: exit 3
  auto* emulate = sub->add_flag("--emulate", args->emulate,
                                "Every device on its emulator, on pseudo-terminals, in real time");
  sub->add_flag("--virtual-time", args->virtual_time,
                "Every device on its emulator over simulated lines, on a virtual clock, as fast as possible")
      ->excludes(emulate);
  sub->add_option("--journal", args->journal_dir,
                  "Directory for the run record (default runs/<recipe>-<time>)");
  sub->add_option("--fault", args->faults_text,
                  "Rehearse a fault (repeatable; --emulate or --virtual-time only): DEVICE:KIND@T[+D] puts\n"
                  "KIND on DEVICE T seconds after the run starts, for D seconds (for ever without +D).\n"
                  "DEVICE: scu, spindle, encoder. KIND: silent (the line carries nothing), disconnect\n"
                  "(the port is lost), corrupt (bits flipped), garbage (random bytes), delay=MS (replies\n"
                  "MS ms late), error (the device's own fault: SCU actuator faults, spindle over-\n"
                  "temperature 31, encoder position alarm). The journal records each fault's start and end.")
      ->check(fault_spec_validator(args->faults));
  commands.on(sub, [&commands, args] { return run_recipe(commands.global, *args); });
}

}  // namespace cellctl::cli

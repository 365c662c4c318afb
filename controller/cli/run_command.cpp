#include "cli/run_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cli/drive.hpp"
#include "cli/exit_codes.hpp"
#include "cli/operator_console.hpp"
#include "cli/run_narrator.hpp"
#include "cli/run_record_info.hpp"
#include "cli/status_printer.hpp"
#include "cli/terminal_screen.hpp"
#include "config/cell_config.hpp"
#include "journal/record_header.hpp"
#include "journal/run_record.hpp"
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

// What Ctrl-C will do, as the cell's config has it.
std::string ctrl_c_hint(config::StopCategory operator_stop) {
  switch (operator_stop) {
    case config::StopCategory::controlled_hold:
      return "Ctrl-C holds the cell (then type stop to end, or reset and unhold to go on); twice: emergency "
             "stop";
    case config::StopCategory::controlled_off:
      return "Ctrl-C stops the cell (controlled, category 1) and ends the run; twice: emergency stop";
    case config::StopCategory::immediate:
      return "Ctrl-C stops the cell at once (category 0) and ends the run";
  }
  return "";
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
  options.journal_dir =
      args.journal_dir.empty() ? default_run_dir(args.recipe) : std::filesystem::path(args.journal_dir);
  options.trace = global.trace;
  options.faults = args.faults;
  const auto info = record_info(cell, global.config, recipe, recipe::unroll(recipe), options.mode);
  options.record_header = journal::record_header(info);

  runtime::CellRun run(cell, recipe, options);
  fmt::print("cellctl: running '{}' {} ({}) on cell '{}' — {}\n", recipe.name, recipe.version, args.recipe,
             cell.name, mode_label(cell, options.mode));
  for (const auto& d : run.links().describe()) fmt::print("  {}\n", d);
  for (const auto& f : options.faults)
    fmt::print("  fault to rehearse: {} — {}\n", f.text, runtime::FaultRehearsal::what(f));
  fmt::print("  run record: {0}/journal.jsonl, plots: {0}/plot.svg, {0}/plot.html\n",
             options.journal_dir.string());

  runtime::RunResult result;
  {
    TerminalScreen screen;
    RunNarrator narrator(screen);
    run.on_journal_line([&narrator](const nlohmann::json& line) { narrator(line); });
    fmt::print("  {}\n", ctrl_c_hint(cell.stops.operator_stop));
    std::vector<std::optional<double>> planned;
    for (const auto& st : info.steps) planned.push_back(st.planned_s);
    StatusPrinter printer(run.status(), cell, screen, std::move(planned));
    OperatorConsole console(run, screen);
    if (console.active())
      screen.message("  type hold, unhold, stop, abort or reset (h, u, s, a, r) and Enter");
    result = run.run(g_interrupted, &g_terminated);
    run.on_journal_line({});
  }
  for (const auto& w : run.realtime_warnings()) spdlog::warn("real-time: {}", w);
  fmt::print("\n{}", result.summary_text);
  if (!result.failure.empty()) fmt::print("failed step: {}\n", result.failure);
  for (const auto& n : result.device_notes) fmt::print("device: {}\n", n);
  if (!result.ended_by.empty()) fmt::print("ended by: {}\n", result.ended_by);
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    const auto& s = result.safety[d];
    if (!s) continue;
    const auto* name = cell::to_string(static_cast<cell::Device>(d));
    if (s->safe == runtime::Safe::unknown)
      fmt::print(stderr, "WARNING: {} safe state UNKNOWN: {}\n", name, s->evidence);
    else
      fmt::print("safe state of {}: {} — {}\n", name, to_string(s->safe), s->evidence);
  }
  fmt::print("{} cycles; {} s of cell time in {:.2f} s", result.cycles,
             fmt::format("{:.2f}", result.duration_s), result.wall_s);
  if (options.mode == runtime::RunMode::virtual_time)
    fmt::print(" ({:.0f}× real time)", result.duration_s / result.wall_s);
  fmt::print("\n{}\n", result.loop_summary);
  fmt::print("run record: {}\n", options.journal_dir.string());

  if (result.any_unknown()) return kExitSafeStateUnknown;
  if (result.final_state == supervisor::State::complete) return kExitOk;
  // Ended by the operator (typed stop/abort, Ctrl-C, SIGTERM) with nothing else gone wrong: 130,
  // however it was asked for; a fault or a failed step: 1.
  return journal::RunRecord::load(options.journal_dir).ended_by_operator() ? kExitInterrupted : kExitFailed;
}

}  // namespace

void add_run_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand(
      "run", "Run a recipe on the cell (hardware, emulators on pseudo-terminals, or virtual time)");
  sub->footer(
      "Devices whose port is 'emulated' in the cell config run as emulators inside cellctl.\n"
      "Exit status: 0 complete, 1 stopped or aborted by a fault or a failed step, 2 bad command line (a bad\n"
      "--fault says why), 3 bad config or recipe (nothing moved), 4 a port could not be opened, 5 a device's\n"
      "safe state is unknown (its stop was never confirmed and nothing bounds it: a spindle that may still\n"
      "turn; look at the cell), 130 ended by the operator (typed stop or abort, Ctrl-C, SIGTERM).\n"
      "After the end, cellctl stays until every device's stop is confirmed or bounded (the SCU: its 0.5 s\n"
      "communication time-out plus scu.stopping_time_ms; the spindle: stop re-sent for 5 s).\n"
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
                  "Directory for the run record (default runs/<recipe file name>-<start time>)");
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

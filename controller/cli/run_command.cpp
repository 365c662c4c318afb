#include "cli/run_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cli/drive.hpp"
#include "cli/operator_console.hpp"
#include "cli/plant_facing.hpp"
#include "cli/run_narrator.hpp"
#include "cli/status_printer.hpp"
#include "cli/terminal_screen.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "jobs/end_state_gate.hpp"
#include "jobs/run_record_info.hpp"
#include "journal/record_header.hpp"
#include "journal/run_record.hpp"
#include "plant_link/link_config.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/dry_run_state.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::cli {

namespace {

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

int run_recipe(const GlobalOptions& global, const std::string& recipe_file, const RunArgs& args) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (const auto problem = run_args_problem(args, cell); !problem.empty()) {
    spdlog::error("{}", problem);
    return kExitUsage;
  }
  recipe::Recipe recipe;
  try {
    recipe = recipe::load_recipe(recipe_file, cell);
  } catch (const recipe::RecipeErrors& e) {
    for (const auto& err : e.errors()) spdlog::error("{}", err.what());
    spdlog::error("{}: {} problem{}; nothing was moved", recipe_file, e.errors().size(),
                  e.errors().size() == 1 ? "" : "s");
    return kExitConfig;
  }
  return run_loaded_recipe(global, cell, recipe, args,
                           args.journal_dir.empty() ? jobs::default_run_dir(recipe_file)
                                                    : std::filesystem::path(args.journal_dir));
}

}  // namespace

std::string fault_problem(const std::vector<runtime::FaultSpec>& faults, bool emulated,
                          const config::CellConfig& cell) {
  if (!faults.empty() && !emulated)
    return "--fault: faults are rehearsed on emulators only: add --emulate or --virtual-time";
  if (auto problem = runtime::FaultRehearsal::problem(faults, cell)) return *problem;
  return {};
}

runtime::RunMode run_mode(const RunArgs& args) {
  return args.virtual_time ? runtime::RunMode::virtual_time
         : args.emulate    ? runtime::RunMode::emulated
                           : runtime::RunMode::hardware;
}

std::string run_args_problem(const RunArgs& args, const config::CellConfig& cell) {
  if (args.power_cycle && !args.emulate && !args.virtual_time)
    return "--power-cycle: only the emulated plant of a dry run can lose its power here: add --emulate or "
           "--virtual-time (on the cell, switch it off)";
  return fault_problem(args.faults, args.emulate || args.virtual_time, cell);
}

int run_loaded_recipe(const GlobalOptions& global, const config::CellConfig& cell,
                      const recipe::Recipe& recipe, const RunArgs& args, const std::filesystem::path& run_dir,
                      const AfterRun& after) {
  runtime::RunOptions options;
  options.mode = run_mode(args);
  options.journal_dir = run_dir;
  options.state_dir = args.state_dir;
  // A dry run's emulated plant keeps its state between runs in the state folder, as a powered cell does
  // (runtime/dry_run_state.hpp): homed in one run, homed in the next.
  if (options.mode != runtime::RunMode::hardware)
    options.emulators = runtime::dry_run_emulator_setup(
        cell, args.state_dir.empty() ? cell.state_dir : std::filesystem::path(args.state_dir),
        args.power_cycle);
  options.trace = global.trace;
  options.faults = args.faults;
  // The plant link's section is read (and so checked) before anything opens: a bad one is exit 3.
  const auto plant_link = plant_link::load_link_config(cell.document.value(), cell);
  // The page's options and token likewise: plain HTTP off loopback, a short token: exit 2.
  std::string page_problem;
  const auto page = page_setup(args.page, page_problem);
  if (!page_problem.empty()) {
    spdlog::error("{}", page_problem);
    return kExitUsage;
  }
  const auto info = jobs::record_info(cell, global.config, recipe, recipe::unroll(recipe), options.mode);
  options.record_header = journal::record_header(info);

  runtime::CellRun run(cell, recipe, options);
  fmt::print("cellctl: running '{}' {} ({}) on cell '{}' — {}\n", recipe.name, recipe.version, recipe.source,
             cell.name, jobs::mode_label(cell, options.mode));
  for (const auto& d : run.links().describe()) fmt::print("  {}\n", d);
  for (const auto& f : options.faults)
    fmt::print("  fault to rehearse: {} — {}\n", f.text, runtime::FaultRehearsal::what(f));
  fmt::print("  run record: {0}/journal.jsonl, plots: {0}/plot.svg, {0}/plot.html\n",
             options.journal_dir.string());

  runtime::RunResult result;
  AfterRunEnd job;
  {
    TerminalScreen screen;
    RunNarrator narrator(screen);
    // The terminal, the plant link and the web page command through one arbiter. This cellctl drives
    // one run: its start is the terminal's, and the run is the arbiter's job until the process ends
    // (a start in Idle, which the arbiter takes).
    command::Tell tell;
    tell.note = [&run](const std::string& words) { run.note_from_operator(words); };
    command::Arbiter arbiter(std::chrono::milliseconds(cell.max_command_age_ms), std::move(tell));
    arbiter.attach(run.port());
    (void)arbiter.start(
        {{command::CommandSource::Origin::terminal, {}, {}}, std::chrono::steady_clock::now(), {}}, [] {
          return command::Taken{command::Taken::How::done, "started by cellctl run"};
        });
    const auto access = plant_link::fixed_run(arbiter, run.status(), to_string(options.mode));
    auto facing = open_plant_facing(cell, plant_link, page,
                                    plant_link ? plant_link->recipes : std::filesystem::path("recipes"),
                                    access, [&screen](const std::string& line) { screen.message(line); });
    jobs::EndStateGate gate(&facing);
    journal::EventListeners listeners{&narrator, &gate};
    run.listen(&listeners);
    fmt::print("  {}\n", ctrl_c_hint(cell.stops.operator_stop));
    std::vector<std::optional<double>> planned;
    for (const auto& st : info.steps) planned.push_back(st.planned_s);
    StatusPrinter printer(run.status(), cell, screen, std::move(planned));
    OperatorConsole console(run, arbiter, screen);
    if (console.active())
      screen.message("  type hold, unhold, stop, abort, reset or clear (h, u, s, a, r, c) and Enter");
    result = run.run(g_interrupted, &g_terminated);
    run.listen(nullptr);
    if (after) job = after(result);  // the job's work saved (the run saved its own: home record, journal)
    gate.release(job.words);         // only now the end state goes out
    facing.close();                  // the link's last tags out (the run's end), then a clean goodbye
  }
  for (const auto& w : run.realtime_warnings()) spdlog::warn("real-time: {}", w);
  fmt::print("\n{}", result.summary_text);
  if (!result.failure.empty()) fmt::print("failed step: {}\n", result.failure);
  for (const auto& n : result.device_notes) fmt::print("device: {}\n", n);
  if (!result.ended_by.empty()) fmt::print("ended by: {}\n", result.ended_by);
  for (const auto& s : result.safety) {
    if (!s) continue;
    const auto name = s->device;
    if (s->safe == runtime::Safe::unknown)
      fmt::print(stderr, "WARNING: {} safe state UNKNOWN: {}\n", name, s->evidence);
    else
      fmt::print("safe state of {}: {} — {}\n", name, to_string(s->safe), s->evidence);
  }
  fmt::print("{} cycles; {} s of cell time in {:.2f} s", result.cycles,
             fmt::format("{:.2f}", result.duration_s), result.wall_s);
  if (options.mode == runtime::RunMode::virtual_time)
    fmt::print(" ({:.0f}× real time)", result.duration_s / result.wall_s);
  fmt::print("\n{}{}\n", result.loop_summary, result.link_summary);
  fmt::print("run record: {}\n", options.journal_dir.string());
  if (!result.home_record.empty()) fmt::print("{}\n", result.home_record);

  if (!job.words.empty()) fmt::print("{}\n", job.words);
  if (result.any_unknown()) return kExitSafeStateUnknown;
  if (job.exit_status) return *job.exit_status;
  if (result.final_state == supervisor::State::complete) return kExitOk;
  // Ended by the operator (typed stop/abort, Ctrl-C, SIGTERM) with nothing else gone wrong: 130,
  // however it was asked for; a fault or a failed step: 1.
  return journal::RunRecord::load(options.journal_dir).ended_by_operator() ? kExitInterrupted : kExitFailed;
}

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

void add_run_options(CLI::App* sub, RunArgs& args) {
  auto* emulate = sub->add_flag("--emulate", args.emulate,
                                "Every device on its emulator (in this process), in real time");
  sub->add_flag("--virtual-time", args.virtual_time,
                "Every device on its emulator over simulated lines, on a virtual clock, as fast as possible")
      ->excludes(emulate);
  sub->add_option("--journal", args.journal_dir,
                  "Directory for the run record (default runs/<recipe file name>-<start time>)");
  sub->add_option("--state-dir", args.state_dir,
                  "Folder of the home record home.json and of a dry run's emulated plant (default: the cell\n"
                  "config's state_dir, 'state')");
  sub->add_flag("--power-cycle", args.power_cycle,
                "A dry run's emulated plant starts as after a power loss: the rods where they were, no\n"
                "actuator initialised (then `require: homed` refuses until homed again)");
  sub->add_option("--fault", args.faults_text,
                  "Rehearse a fault (repeatable; --emulate or --virtual-time only): DEVICE:KIND@T[+D] puts\n"
                  "KIND on DEVICE T seconds after the run starts, for D seconds (for ever without +D).\n"
                  "DEVICE: scu, spindle, encoder. KIND: silent (the line carries nothing), disconnect\n"
                  "(the port is lost), corrupt (bits flipped), garbage (random bytes), delay=MS (replies\n"
                  "MS ms late), error (the device's own fault: SCU actuator faults, spindle over-\n"
                  "temperature 31, encoder position alarm). The journal records each fault's start and end.")
      ->check(fault_spec_validator(args.faults));
  add_page_options(sub, args.page);
}

void add_run_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand(
      "run", "Run a recipe on the cell (hardware, emulators in real time, or virtual time)");
  sub->footer(
      "Devices whose port is 'emulated' in the cell config run as emulators inside cellctl.\n"
      "A recipe's `require: {homed: [...]}` checks the home record (<state_dir>/home.json) against the\n"
      "devices before any motion; its `home: [...]` steps home axes and write that record.\n"
      "Exit status: 0 complete, 1 stopped or aborted by a fault or a failed step, 2 bad command line\n"
      "(a bad --fault says why), 3 bad config or recipe (nothing moved), 4 a port could not be opened,\n"
      "5 a device's safe state is unknown (its stop was never confirmed and nothing bounds it: a spindle\n"
      "that may still turn; look at the cell), 130 ended by the operator (typed stop or abort, Ctrl-C,\n"
      "SIGTERM).\n"
      "After the end, cellctl stays until every device's stop is confirmed or bounded (the SCU: its 0.5 s\n"
      "communication time-out plus scu.stopping_time_ms; the spindle: stop re-sent for 5 s).\n"
      "Ctrl-C once: operator stop (category from stops.operator; 2 holds the cell); twice: emergency stop.\n"
      "SIGTERM: a controlled stop (category 1).");
  auto args = std::make_shared<RunArgs>();
  auto recipe_file = std::make_shared<std::string>();
  sub->add_option("recipe", *recipe_file, "Recipe file (YAML)")->required();  // unreadable: exit 3
  add_run_options(sub, *args);
  commands.on(sub,
              [&commands, args, recipe_file] { return run_recipe(commands.global, *recipe_file, *args); });
}

}  // namespace cellctl::cli

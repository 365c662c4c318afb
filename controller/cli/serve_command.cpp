#include "cli/serve_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli/drive.hpp"
#include "cli/plant_facing.hpp"
#include "cli/run_command.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulator_setup.hpp"
#include "exit_codes/exit_codes.hpp"
#include "jobs/job_scheduler.hpp"
#include "jobs/run_record_info.hpp"
#include "motion/planned_time.hpp"
#include "plant_link/link_config.hpp"

namespace cellctl::cli {
namespace {

struct ServeArgs {
  bool emulate = false;
  bool virtual_time = false;
  std::string runs_dir = "runs";
  std::string state_dir;
  std::string recipes;
  std::vector<std::string> faults_text;
  std::vector<runtime::FaultSpec> faults;  // rehearsed in every job (dry runs only)
  PageArgs page;                           // --http and its options
};

// Each recipe's planned time on the page's Start list: the planner's (the page does not see it), with
// the spindle's ramps where they are known — an emulated converter's; a real one's are its own
// parameters, which the config does not hold (its run-ups are then counted apart).
recipe::ProgramTimer recipe_timer(const config::CellConfig& cell, runtime::RunMode mode) {
  std::optional<motion::SpindleRamps> ramps;
  if (mode != runtime::RunMode::hardware)
    if (const auto setup = emulation::load_emulator_setup(cell); setup.spindle)
      ramps = motion::SpindleRamps{setup.spindle->ramp_up_hz_s, setup.spindle->ramp_down_hz_s};
  return [core = static_cast<const config::CellCore&>(cell), ramps](
             const recipe::Program& program, std::span<const std::optional<double>> start_mm) {
    return motion::planned_time(core, program, start_mm, ramps);
  };
}

int serve(const GlobalOptions& global, const ServeArgs& args) {
  const auto cell = device_seam::load_cell_config(global.config);
  // A bad section: exit 3, before anything opens.
  auto link_config = plant_link::load_link_config(cell.document.value(), cell);
  std::string page_problem;  // plain HTTP off loopback, a short token: refused before anything opens
  auto page = page_setup(args.page, page_problem);
  if (!page_problem.empty()) {
    spdlog::error("serve: {}", page_problem);
    return kExitUsage;
  }
  if (const auto problem = fault_problem(args.faults, args.emulate || args.virtual_time, cell);
      !problem.empty()) {
    spdlog::error("serve: {}", problem);
    return kExitUsage;
  }
  if (!link_config && !page) {
    spdlog::error(
        "serve: nothing could start a job: give --http ADDR:PORT for the operator page, or a plant_link: "
        "section "
        "in {} for the plant's MQTT broker",
        global.config);
    return kExitUsage;
  }
  // The recipes a start names: --recipes, else the plant link's folder, else ./recipes.
  const std::filesystem::path recipes = !args.recipes.empty() ? std::filesystem::path(args.recipes)
                                        : link_config         ? link_config->recipes
                                                              : std::filesystem::path("recipes");
  if (link_config) link_config->recipes = recipes;
  jobs::SchedulerOptions options;
  options.mode = args.virtual_time ? runtime::RunMode::virtual_time
                 : args.emulate    ? runtime::RunMode::emulated
                                   : runtime::RunMode::hardware;
  options.config_file = global.config;
  options.runs_dir = args.runs_dir;
  options.state_dir = args.state_dir;
  options.trace = global.trace;
  options.faults = args.faults;
  options.max_command_age = std::chrono::milliseconds(cell.max_command_age_ms);
  jobs::JobScheduler scheduler(cell, options);

  const auto say = [](const std::string& line) {
    fmt::print("{}\n", line);
    std::fflush(stdout);
  };
  say(fmt::format("cellctl serve: cell '{}' — {}; standing by for the plant and the operator page", cell.name,
                  jobs::mode_label(cell, options.mode)));
  // Read before the page and the plant link open: their first Idle shows the cell as it stands.
  scheduler.look(say);
  if (page) {
    page->options.runs = args.runs_dir;  // the page's run history
    page->options.plan = recipe_timer(cell, options.mode);
  }
  auto facing = open_plant_facing(cell, link_config, page, recipes, scheduler.access(), say);
  scheduler.listen(&facing);
  say(fmt::format("  jobs: start (a recipe in {}), home, teach-in; run records under {}/", recipes.string(),
                  args.runs_dir));
  say("  Ctrl-C: the job in progress gets it (as in `cellctl run`); with no job, it ends cellctl serve");
  const int status = scheduler.serve(g_interrupted, g_terminated, say);
  facing.close();
  say(fmt::format("cellctl serve: ended after {} job{}", scheduler.jobs_done(),
                  scheduler.jobs_done() == 1 ? "" : "s"));
  if (status == kExitSafeStateUnknown)
    fmt::print(stderr, "WARNING: a device's safe state is UNKNOWN: look at the cell\n");
  return status;
}

}  // namespace

void add_serve_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand("serve",
                                 "Stand by for the plant (MQTT) and the operator page: run the recipes, "
                                 "homing and Teach-Ins they start");
  sub->footer(
      "Jobs, one at a time, each with its own run record under --runs: `start` a recipe from the recipe\n"
      "folder (validated first: its problems come back with file:line:col), `home` (axes as the config's\n"
      "homing: says), `teach-in` (the encoder over a distance of its axis, moved by the SCU; the verified\n"
      "result is written into the config, which is then read again). They come from the plant link's\n"
      "cmd/<word> topics (the config's plant_link: section) or the operator page's buttons (--http, with "
      "its\n"
      "token). Every job is a run of the same cycle as `cellctl run`: hold, unhold, stop, abort and reset "
      "go\n"
      "to it (a hold or a stop ends a Teach-In, the encoder's parameters restored). A stop or abort while a\n"
      "job starts cancels it or stops it before any motion. A job's end state is told once its work is\n"
      "saved (home record, taught config). A start is refused until the job in progress has ended, and for\n"
      "good after a job left a device's safe state unknown or the encoder's parameters unconfirmed.\n"
      "Exit status: 0 ended by SIGTERM (a job in progress gets its controlled stop first), 130 Ctrl-C with\n"
      "no job in progress, 2 bad command line or nothing to take commands from, 3 bad config, 5 a job left\n"
      "a device's safe state unknown or the encoder's parameters unconfirmed.");
  auto args = std::make_shared<ServeArgs>();
  auto* emulate = sub->add_flag("--emulate", args->emulate,
                                "Every device on its emulator (in this process), in real time");
  sub->add_flag("--virtual-time", args->virtual_time,
                "Every device on its emulator over simulated lines, on a virtual clock, as fast as possible")
      ->excludes(emulate);
  sub->add_option("--runs", args->runs_dir, "Folder of the jobs' run records")->capture_default_str();
  sub->add_option(
      "--state-dir", args->state_dir,
      "Folder of the home record (home.json; home.<mode>.json for dry runs; default: the cell config's "
      "state_dir, 'state')");
  sub->add_option("--recipes", args->recipes,
                  "Folder of the recipes a start names (default: the plant_link section's, else ./recipes)");
  sub->add_option(
         "--fault", args->faults_text,
         "Rehearse a fault in every job (repeatable; --emulate or --virtual-time only), as `cellctl run\n"
         "--fault`: DEVICE:KIND@T[+D], T seconds after each job's start")
      ->check(fault_spec_validator(args->faults));
  add_page_options(sub, args->page);
  commands.on(sub, [&commands, args] { return serve(commands.global, *args); });
}

}  // namespace cellctl::cli

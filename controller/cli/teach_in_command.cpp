#include "cli/teach_in_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "cli/confirm.hpp"
#include "cli/drive.hpp"
#include "cli/run_command.hpp"
#include "cli/terminal_screen.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "jobs/run_record_info.hpp"
#include "jobs/teach_in_job.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/fault_rehearsal.hpp"

namespace cellctl::cli {
namespace {

struct TeachInArgs {
  std::string axis;
  double distance_mm = 0.0;
  std::optional<double> from_mm;
  bool manual = false;
  std::optional<double> speed_mm_s;
  double tolerance_mm = 0.05;
  bool yes = false;  // confirmed beforehand (scripts)
  RunArgs run;       // --emulate, --virtual-time, --journal, --fault …, as `cellctl run`
};

std::filesystem::path default_dir(const std::string& axis) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &utc);
  return std::filesystem::path("runs") / fmt::format("teach-in-{}-{}", axis, stamp);
}

// What the Teach-In will move and write, said before anything moves (as `cellctl home` does), so the
// operator answers knowing it: the axis, from where to where and back, at what speed, and the file.
// Printed with --yes too: a script's log says what moved.
std::string plan(const config::CellConfig& cell, const routines::TeachInRequest& r,
                 const std::filesystem::path& written, bool dry_run) {
  const auto& axis = cell.axes.at(static_cast<std::size_t>(r.axis));
  const auto start = r.from_mm ? fmt::format("{:g} mm", *r.from_mm) : std::string("where it stands");
  const auto end = r.from_mm ? fmt::format("{:g} mm", *r.from_mm + r.distance_mm)
                             : fmt::format("{:g} mm further", r.distance_mm);
  std::string q = r.manual ? fmt::format(
                                 "Teach-In of the encoder on axis {}: YOU move {} by hand from {} to {} and "
                                 "back, when asked (the SCU moves nothing)",
                                 axis.name, axis.name, start, end)
                           : fmt::format(
                                 "Teach-In of the encoder on axis {}: the SCU MOVES {}{} from {} to {} and "
                                 "back at {:g} mm/s",
                                 axis.name, axis.name, r.from_mm ? fmt::format(" to {}, then", start) : "",
                                 start, end, r.speed_mm_s);
  q += fmt::format(
      ";\n  the encoder is re-parameterised for it, and the verified resolution is written into {}{}\n",
      written.string(), dry_run ? " (a dry run's copy: the cell's config is left as it is)" : "");
  return q;
}

int teach_in(const GlobalOptions& global, const TeachInArgs& args) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (const auto problem = run_args_problem(args.run, cell); !problem.empty()) {
    spdlog::error("{}", problem);
    return kExitUsage;
  }
  const auto asked = jobs::teach_in_request(
      cell, {args.axis, args.distance_mm, args.from_mm, args.manual, args.speed_mm_s, args.tolerance_mm});
  if (const auto* why = std::get_if<std::string>(&asked)) {
    spdlog::error("teach-in: {}", *why);
    return kExitUsage;
  }
  const auto& request = std::get<routines::TeachInRequest>(asked);
  const bool dry_run = run_mode(args.run) != runtime::RunMode::hardware;
  fmt::print(
      "{}",
      plan(cell, request,
           jobs::teach_in_destination(global.config, cell, run_mode(args.run), args.run.state_dir), dry_run));
  switch (confirm("Start the Teach-In now? Keep clear of the cell.", args.yes)) {
    case Confirmation::confirmed:
      break;
    case Confirmation::no_terminal:
      spdlog::error(
          "teach-in: confirmation needed and no terminal to ask on: add --yes to run a Teach-In from a "
          "script");
      return kExitUsage;
    case Confirmation::declined:
      fmt::print("not confirmed: nothing moved, nothing written\n");
      return kExitFailed;
  }
  const auto run_dir =
      args.run.journal_dir.empty() ? default_dir(args.axis) : std::filesystem::path(args.run.journal_dir);
  const auto recipe = jobs::teach_in_recipe(cell, request, run_dir);
  // The same cycle as every job; once it has ended, the verified result goes into the config.
  return run_loaded_recipe(global, cell, recipe, args.run, run_dir, [&](const runtime::RunResult& r) {
    const auto record =
        jobs::record_teach_in(global.config, cell, r, run_mode(args.run), args.run.state_dir, args.manual);
    return AfterRunEnd{record.words, record.write_failed ? std::optional(kExitFailed)
                                     : record.written    ? std::optional(kExitOk)
                                                         : std::nullopt};
  });
}

}  // namespace

void add_teach_in_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand(
      "teach-in",
      "Teach the encoder its resolution over a distance of an axis (manual 4.4.2), verify it, and "
      "write it into the cell config");
  sub->footer(
      "Switches the encoder to the manual's prerequisites (commissioning mode, scaling on, units per total\n"
      "measuring range, offset 0), moves the axis with the SCU from the start over the distance without\n"
      "crossing the encoder's native zero (--manual: tells the operator what to move and waits for Enter),\n"
      "ends the Teach-In, verifies by moving back, then writes scaling, units_select, measuring_units and\n"
      "counts_per_mm into the config's encoder section (temp file + rename; the old file kept as FILE.bak).\n"
      "An abort (Ctrl-C), a fault or a failed verification restores the encoder's configured parameters\n"
      "and leaves the config untouched. The reference is the SCU's position (with --manual: the operator's\n"
      "marks). Exit status: 0 taught and written, 1 failed, 2 bad command line, 3 bad config, 4 a port\n"
      "could not be opened, 5 a device's safe state is unknown, 130 ended by the operator.\n"
      "It says what will move and be written and asks yes first (--yes for scripts; without a terminal and\n"
      "without --yes it refuses, exit 2; any other answer: exit 1, nothing moved).\n"
      "It runs in the same cycle as `cellctl run` (monitor, safe stop, run record with samples and plot);\n"
      "Ctrl-C and the typed commands act as there; with --manual, Enter confirms each move.");
  auto args = std::make_shared<TeachInArgs>();
  sub->add_option("axis", args->axis, "The axis the encoder measures (e.g. x)")->required();
  sub->add_option("--distance", args->distance_mm, "Travel in mm, in + direction from the start")
      ->required()
      ->check(CLI::Range(0.1, 10000.0));
  sub->add_option("--from", args->from_mm, "Start position in mm (default: where the axis stands)");
  sub->add_flag("--manual", args->manual, "The operator moves the axis (Enter after each move)");
  sub->add_option("--speed", args->speed_mm_s, "Speed of the moves in mm/s (default: 5, at most the axis's)")
      ->check(CLI::Range(0.01, 1000.0));
  sub->add_option("--tolerance", args->tolerance_mm,
                  "Verification: the encoder's distance back may differ from the SCU's by this much (mm)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 10.0));
  sub->add_flag("-y,--yes", args->yes, "Do not ask before the Teach-In moves the axis (for scripts)");
  add_run_options(sub, args->run);
  commands.on(sub, [&commands, args] { return teach_in(commands.global, *args); });
}

}  // namespace cellctl::cli

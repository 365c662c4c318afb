#include "cli/teach_in_command.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "cli/drive.hpp"
#include "cli/exit_codes.hpp"
#include "cli/run_command.hpp"
#include "cli/run_record_info.hpp"
#include "cli/teach_in_job.hpp"
#include "cli/terminal_screen.hpp"
#include "config/cell_config.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/teach_in_run.hpp"

namespace cellctl::cli {
namespace {

struct TeachInArgs {
  std::string axis;
  double distance_mm = 0.0;
  std::optional<double> from_mm;
  bool manual = false;
  std::optional<double> speed_mm_s;
  double tolerance_mm = 0.05;
  bool emulate = false;
  bool virtual_time = false;
  std::string journal_dir;
  std::vector<std::string> faults_text;
  std::vector<runtime::FaultSpec> faults;
};

bool line_typed() {
  pollfd p{STDIN_FILENO, POLLIN, 0};
  if (::poll(&p, 1, 0) <= 0) return false;
  char buf[256];
  return ::read(STDIN_FILENO, buf, sizeof buf) > 0;
}

std::filesystem::path default_dir(const std::string& axis) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &utc);
  return std::filesystem::path("runs") / fmt::format("teach-in-{}-{}", axis, stamp);
}

// The verified result into the config, the changes printed.
int write_result(const std::filesystem::path& config_file, const config::CellConfig& cell,
                 const runtime::TeachInOutcome& o) {
  try {
    const auto change = write_teach_in_result(config_file, cell, o);
    for (const auto& line : change.changed) fmt::print("  {}\n", line);
    fmt::print("{} written; the previous config is {}\n", config_file.string(), change.backup.string());
    return kExitOk;
  } catch (const std::exception& e) {
    spdlog::error("Teach-In verified, but {} was not changed: {}", config_file.string(), e.what());
    return kExitFailed;
  }
}

int teach_in(const GlobalOptions& global, const TeachInArgs& args) {
  const auto cell = config::load_cell_config(global.config);
  if (const auto problem = fault_problem(args.faults, args.emulate || args.virtual_time, cell);
      !problem.empty()) {
    spdlog::error("{}", problem);
    return kExitUsage;
  }
  const auto asked = teach_in_request(
      cell, {args.axis, args.distance_mm, args.from_mm, args.manual, args.speed_mm_s, args.tolerance_mm});
  if (const auto* why = std::get_if<std::string>(&asked)) {
    spdlog::error("teach-in: {}", *why);
    return kExitUsage;
  }
  const auto& request = std::get<routines::TeachInRequest>(asked);

  runtime::TeachInRunOptions options;
  options.mode = args.virtual_time ? runtime::RunMode::virtual_time
                 : args.emulate    ? runtime::RunMode::emulated
                                   : runtime::RunMode::hardware;
  options.journal_dir =
      args.journal_dir.empty() ? default_dir(args.axis) : std::filesystem::path(args.journal_dir);
  options.trace = global.trace;
  options.faults = args.faults;
  options.record_header = teach_in_record_header(global.config, args.axis, args.distance_mm, options.mode);

  runtime::TeachInRun run(cell, request, options);
  fmt::print("cellctl: Teach-In of the encoder on axis {} over {:g} mm{} — {}\n", args.axis, args.distance_mm,
             args.manual ? ", moved by the operator" : ", moved by the SCU", mode_label(cell, options.mode));
  for (const auto& f : options.faults)
    fmt::print("  fault to rehearse: {} — {}\n", f.text, runtime::FaultRehearsal::what(f));
  fmt::print("  record: {}/journal.jsonl; Ctrl-C aborts (the encoder's parameters are restored)\n",
             options.journal_dir.string());
  runtime::TeachInOutcome o;
  {
    TerminalScreen screen;
    std::string last_prompt;
    o = run.run(g_interrupted, [&](const runtime::TeachInProgress& p) {
      screen.status(fmt::format("{:6.1f} s  {:<40}  SCU {:8.3f} mm  encoder {:10.3f} mm", p.t,
                                routines::to_string(p.phase), p.scu_mm, p.encoder_mm));
      if (!p.prompt.empty() && p.prompt != last_prompt) {
        screen.message(fmt::format("  >> {} (press Enter)", p.prompt));
        last_prompt = p.prompt;
      }
      if (!p.prompt.empty() && line_typed()) run.confirm();
    });
  }
  for (const auto& n : o.device_notes) fmt::print("device: {}\n", n);
  if (!o.done) {
    fmt::print("Teach-In failed: {}\n", o.failure);
    fmt::print("{}; {} not changed\n",
               o.restored ? "the encoder's configured parameters are restored"
                          : "the encoder's configured parameters could NOT be confirmed restored: check with "
                            "`cellctl encoder diag` before any run",
               global.config);
    return o.interrupted ? kExitInterrupted : kExitFailed;
  }
  fmt::print(
      "Teach-In done: total resolution {} (units per maximum total measuring range), {:g} units per mm;\n"
      "  verified: moving back, the encoder measured {:.4f} mm, the {} {:.4f} mm\n",
      o.result.total_resolution, o.units_per_mm, o.result.encoder_distance_mm,
      args.manual ? "distance given" : "SCU", o.result.scu_back_mm);
  return write_result(global.config, cell, o);
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
      "could not be opened, 130 aborted.");
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
  auto* emulate =
      sub->add_flag("--emulate", args->emulate, "Every device on its emulator, on pseudo-terminals");
  sub->add_flag("--virtual-time", args->virtual_time, "Every device on its emulator, on a virtual clock")
      ->excludes(emulate);
  sub->add_option("--journal", args->journal_dir,
                  "Directory for the record (default runs/teach-in-AXIS-<time>)");
  sub->add_option("--fault", args->faults_text, "Rehearse a fault, as `cellctl run --fault` (repeatable)")
      ->check(fault_spec_validator(args->faults));
  commands.on(sub, [&commands, args] { return teach_in(commands.global, *args); });
}

}  // namespace cellctl::cli

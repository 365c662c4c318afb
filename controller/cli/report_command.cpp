#include "cli/report_command.hpp"

#include <fmt/format.h>

#include <fstream>
#include <memory>
#include <stdexcept>

#include "exit_codes/exit_codes.hpp"
#include "journal/run_record.hpp"
#include "journal/run_report.hpp"

namespace cellctl::cli {
namespace {

struct ReportArgs {
  std::string run_dir;
  std::string csv;
};

int run_report(const ReportArgs& args) {
  const auto run = journal::RunRecord::load(args.run_dir);
  fmt::print("{}", journal::report_text(run));
  if (!args.csv.empty()) {
    std::ofstream out(args.csv);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", args.csv));
    journal::write_csv(run, out);
    out.close();
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", args.csv));
    fmt::print("samples: {} rows in {}\n", run.samples().size(), args.csv);
  }
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand("report",
                                 "Summarise a run record: steps (planned and actual time), faults, "
                                 "max following error per axis, loop timing, spindle");
  auto args = std::make_shared<ReportArgs>();
  sub->add_option("run", args->run_dir, "Run record directory (runs/<recipe>-<time>) or its journal.jsonl")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--csv", args->csv,
                  "Also write the samples to this CSV file (t_s, step, positions, spindle)");
  sub->footer("Exit status: 0 done, 1 the record cannot be read (file:line named), 2 bad command line.");
  commands.on(sub, [args] { return run_report(*args); });
}

}  // namespace cellctl::cli

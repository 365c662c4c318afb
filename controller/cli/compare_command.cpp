#include "cli/compare_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "exit_codes/exit_codes.hpp"
#include "journal/plot_html.hpp"
#include "journal/plot_svg.hpp"
#include "journal/run_compare.hpp"
#include "journal/run_record.hpp"

namespace cellctl::cli {
namespace {

struct CompareArgs {
  std::string a, b;
  std::string out_dir = ".";
  bool force = false;
};

int run_compare(const CompareArgs& args) {
  const auto a = journal::RunRecord::load(args.a);
  const auto b = journal::RunRecord::load(args.b);
  if (const auto why = journal::different_recipes(a, b)) {
    if (!args.force) {
      spdlog::error("{}; nothing compared (--force compares them anyway, step by step number)", *why);
      return kExitUsage;
    }
    spdlog::warn("{}; compared anyway (--force)", *why);
  }
  fmt::print("{}", journal::compare_text(a, b));
  const std::filesystem::path dir = args.out_dir;
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "compare.svg") << journal::render_svg({&a, &b});
  std::ofstream(dir / "compare.html") << journal::render_html({&a, &b});
  fmt::print("overlaid: {}, {}\n", (dir / "compare.svg").string(), (dir / "compare.html").string());
  return kExitOk;
}

}  // namespace

void add_compare_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand(
      "compare", "Compare two runs of one recipe: per-step differences, and both overlaid in one plot");
  auto args = std::make_shared<CompareArgs>();
  sub->add_option("run_a", args->a, "First run record (e.g. the virtual-time dry run)")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("run_b", args->b, "Second run record (e.g. the real run)")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--out", args->out_dir, "Where to write compare.svg and compare.html")
      ->capture_default_str();
  sub->add_flag("--force", args->force, "Compare runs of different recipes (or of unknown ones) anyway");
  sub->footer(
      "Runs are matched step by step by number; each run's time starts at its own start.\n"
      "Exit status: 0 done, 1 a record cannot be read, 2 bad command line or runs of different recipes.");
  commands.on(sub, [args] { return run_compare(*args); });
}

}  // namespace cellctl::cli

// The long soak (soak.hpp): demo runs with random rehearsed faults and operator commands until the
// virtual time asked for is done; a line per run, the figures at the end; exit status 1 when any run
// broke a rule (its record is kept under --dir), 0 otherwise. Run it from the ASan build so that a
// leak ends it with the sanitizer's report.
//
//   fault_soak [--virtual-hours H] [--seed N] [--first K] [--dir DIR]
//     --virtual-hours  how much virtual time to soak (default 1)
//     --seed           the random plan's seed (default 1); run K of seed N is the same every time
//     --first          start at run K (to replay a finding)
//     --dir            where a failed run's record stays (default a temporary directory)

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <map>
#include <string>

#include "faults/fault_matrix.hpp"
#include "faults/soak.hpp"
#include "recipe/recipe_loader.hpp"

using namespace cellctl;
using namespace cellctl::faults;

int main(int argc, char** argv) {
  double hours = 1.0;
  std::uint64_t seed = 1, first = 0;
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("cellctl-soak-" + std::to_string(::getpid()));
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--virtual-hours") == 0 && has_value) {
      hours = std::stod(argv[++i]);
    } else if (std::strcmp(argv[i], "--seed") == 0 && has_value) {
      seed = std::stoull(argv[++i]);
    } else if (std::strcmp(argv[i], "--first") == 0 && has_value) {
      first = std::stoull(argv[++i]);
    } else if (std::strcmp(argv[i], "--dir") == 0 && has_value) {
      dir = argv[++i];
    } else {
      fmt::print(stderr, "usage: {} [--virtual-hours H] [--seed N] [--first K] [--dir DIR]\n", argv[0]);
      return 2;
    }
  }
  const auto cell = matrix_cell();
  const auto recipe =
      recipe::load_recipe(std::filesystem::path(CELLCTL_SOURCE_DIR) / "recipes/demo.yaml", cell);
  const auto wall = std::chrono::steady_clock::now();
  double virtual_s = 0.0, longest_s = 0.0;
  std::size_t runs = 0, faults = 0, commands = 0, failed = 0, stuck = 0;
  std::map<std::string, std::size_t> outcomes;
  std::array<std::map<std::string, std::size_t>, cell::kDevices> safe;
  for (std::uint64_t i = first; virtual_s < hours * 3600.0; ++i) {
    const auto run = soak_run(soak_plan(seed, i), cell, recipe, dir / std::to_string(i));
    fmt::print("run {}: {}\n", i, describe(run));
    std::fflush(stdout);
    ++runs;
    virtual_s += run.virtual_s;
    longest_s = std::max(longest_s, run.virtual_s);
    faults += run.faults_injected;
    commands += run.plan.commands.size();
    ++outcomes[run.outcome.empty() ? "(no summary)" : run.outcome];
    for (const auto d : kDevices) {
      const auto& s = run.devices.safe[static_cast<std::size_t>(d)];
      ++safe[static_cast<std::size_t>(d)][s ? std::string(to_string(*s)) : "-"];
    }
    if (!run.violations.empty()) ++failed;
    for (const auto& v : run.violations) stuck += v.rfind("stuck", 0) == 0;
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  fmt::print(
      "\nseed {}: {} runs, {:.2f} h of virtual time in {:.0f} s wall ({:.0f}× real time); longest run {:.1f} "
      "s\n",
      seed, runs, virtual_s / 3600.0, wall_s, virtual_s / wall_s, longest_s);
  fmt::print("faults injected {}, operator commands {}\n", faults, commands);
  std::string o;
  for (const auto& [k, n] : outcomes) o += fmt::format(" {} {}", k, n);
  fmt::print("outcomes:{}\n", o);
  for (const auto d : kDevices) {
    std::string s;
    for (const auto& [k, n] : safe[static_cast<std::size_t>(d)]) s += fmt::format(" {} {}", k, n);
    fmt::print("{} safe:{}\n", cell::to_string(d), s);
  }
  fmt::print("stuck runs {}, runs breaking a rule {}{}\n", stuck, failed,
             failed ? fmt::format(" (records under {})", dir.string()) : std::string());
  return failed ? 1 : 0;
}

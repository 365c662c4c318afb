// The soak (soak.hpp), short: a few demo runs with seeded random faults and operator commands, each
// judged on what must hold whatever happened (ended in bounded time with a summary, no `unknown`
// where a stop could have been confirmed, the plant at rest unless said otherwise). ASan finds leaks.
// The long soak is `fault_soak --virtual-hours 1` (README).

#include "faults/soak.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <iostream>

#include "faults/fault_matrix.hpp"
#include "recipe/recipe_loader.hpp"

namespace cellctl::faults {
namespace {

constexpr std::uint64_t kSeed = 20261124;
constexpr std::uint64_t kRuns = 4;

TEST(Soak, DemoRunsWithRandomFaultsAndCommandsEndSafe) {
  const auto cell = matrix_cell();
  const auto recipe =
      recipe::load_recipe(std::filesystem::path(CELLCTL_SOURCE_DIR) / "recipes/demo.yaml", cell);
  const auto work =
      std::filesystem::temp_directory_path() / ("cellctl-soak-test-" + std::to_string(::getpid()));
  double virtual_s = 0.0;
  std::size_t faults = 0;
  for (std::uint64_t i = 0; i < kRuns; ++i) {
    const auto run = soak_run(soak_plan(kSeed, i), cell, recipe, work / std::to_string(i));
    std::cout << "  run " << i << ": " << describe(run) << "\n";
    for (const auto& v : run.violations) ADD_FAILURE() << "seed " << kSeed << " run " << i << ": " << v;
    virtual_s += run.virtual_s;
    faults += run.faults_injected;
  }
  std::cout << "  " << kRuns << " runs, " << virtual_s << " s of virtual time, " << faults
            << " faults injected\n";
  EXPECT_GT(faults, 0u) << "the seed injects no fault: choose another";
  std::filesystem::remove_all(work);
}

}  // namespace
}  // namespace cellctl::faults

#pragma once
// The soak of issue 12 (part 7): the demo recipe run again and again in virtual time, each run with
// random rehearsed faults (`--fault`'s machinery: any device, any kind, at any time, for a while or
// for ever) and random operator commands (hold, unhold after it, stop), all drawn from one seed, so a
// finding is replayed by its seed and run number. Every run is judged on what must hold whatever
// happened:
//  - it ends by itself within a bound (kStuckS of virtual time; the demo takes 91 s, a hold at most
//    kMaxHoldS more, a safe stop seconds), with its journal closed by a summary;
//  - the summary says per device how its safe state is known, and a device is `unknown` only where
//    the fault left no way to confirm a stop: a line fault on that very device on until less than
//    1.5 s before the end (a retry, the reply, the spindle's run-down from 400 Hz);
//  - the emulated plant is at rest at the end, unless cellctl says the device that moves it is
//    `unknown` (then it must say so, and does).
// Leaks are the sanitizer's to find: run it in the ASan build.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "faults/run_truth.hpp"
#include "recipe/recipe.hpp"

namespace cellctl::faults {

inline constexpr double kStuckS = 300.0;  // virtual seconds a run may take before it counts as stuck
inline constexpr double kMaxHoldS = 5.0;

struct SoakCommand {
  double at_s = 0.0;
  std::string command;  // hold, unhold, stop
};

struct SoakPlan {
  std::vector<std::string> faults;  // --fault texts
  std::vector<SoakCommand> commands;
};

// The plan of run `index` of the soak seeded with `seed`: the same every time.
[[nodiscard]] SoakPlan soak_plan(std::uint64_t seed, std::uint64_t index);

struct SoakRun {
  SoakPlan plan;
  double virtual_s = 0.0;  // the run's length on its clock
  double wall_s = 0.0;
  std::string outcome;  // the summary's
  DeviceSafety devices;
  std::size_t faults_injected = 0;      // fault_injected events (a fault after the end is none)
  std::vector<std::string> violations;  // what must hold and did not; empty: the run is fine
};

// Runs one planned run of `recipe` on `cell`; its record goes to `dir` (removed when the run is fine).
[[nodiscard]] SoakRun soak_run(const SoakPlan& plan, const config::CellConfig& cell,
                               const recipe::Recipe& recipe, const std::filesystem::path& dir);

// One line for a log: "faults [...] commands [...] → outcome after 91.2 s; scu observed, …; ok".
[[nodiscard]] std::string describe(const SoakRun& run);

}  // namespace cellctl::faults

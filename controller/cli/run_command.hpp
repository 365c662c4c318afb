#pragma once
// `cellctl run RECIPE`: runs a recipe on the cell — hardware, emulators in real time, or
// emulators in virtual time — with live status, a run record and a summary at the end. `cellctl home`
// runs its homing recipe through the same path (run_loaded_recipe).

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/plant_facing.hpp"
#include "config/cell_config.hpp"
#include "recipe/recipe.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::cli {

// How a recipe is run: the options `run` and `home` share.
struct RunArgs {
  bool emulate = false;
  bool virtual_time = false;
  std::string journal_dir;
  std::string state_dir;
  bool power_cycle = false;  // a dry run's emulated plant starts as after a power loss
  std::vector<std::string> faults_text;
  std::vector<runtime::FaultSpec> faults;  // parsed (and so checked) by the option's validator
  PageArgs page;                           // --http and its options
};

// --emulate, --virtual-time, --journal, --state-dir, --fault and the page's options on `sub`.
void add_run_options(CLI::App* sub, RunArgs& args);

// What a job does once its run has ended (a Teach-In writes what it taught into the config): what it
// did in words (printed, and appended to the end state's reason, which is told only now), and its exit
// status, or none to keep the run's.
struct AfterRunEnd {
  std::string words;
  std::optional<int> exit_status;
};
using AfterRun = std::function<AfterRunEnd(const runtime::RunResult&)>;

// Runs a loaded recipe: banner, live status, operator console, the summary; its exit status.
// `run_dir` is the run record's folder. A device's safe state unknown is exit 5 whatever `after` says.
[[nodiscard]] int run_loaded_recipe(const GlobalOptions& global, const config::CellConfig& cell,
                                    const recipe::Recipe& recipe, const RunArgs& args,
                                    const std::filesystem::path& run_dir, const AfterRun& after = {});

// The mode the options ask for: --virtual-time, --emulate, or the hardware.
[[nodiscard]] runtime::RunMode run_mode(const RunArgs& args);

// A bad --fault for this cell, or --fault without an emulated mode: the reason (exit 2), else empty.
[[nodiscard]] std::string run_args_problem(const RunArgs& args, const config::CellConfig& cell);

void add_run_command(CLI::App& app, Commands& commands);
// --fault's validator (run and teach-in): the text becomes a FaultSpec in `out`, or the reason is
// CLI11's error (exit 2).
[[nodiscard]] CLI::Validator fault_spec_validator(std::vector<runtime::FaultSpec>& out);
// Faults asked for where they cannot be rehearsed — a run that is not emulated, a device the cell
// lacks: the reason (exit 2), else empty.
[[nodiscard]] std::string fault_problem(const std::vector<runtime::FaultSpec>& faults, bool emulated,
                                        const config::CellConfig& cell);

}  // namespace cellctl::cli

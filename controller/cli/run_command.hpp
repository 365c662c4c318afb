#pragma once
// `cellctl run RECIPE`: runs a recipe on the cell — hardware, emulators in real time, or
// emulators in virtual time — with live status, a run record and a summary at the end. `cellctl home`
// runs its homing recipe through the same path (run_loaded_recipe).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/plant_facing.hpp"
#include "config/cell_config.hpp"
#include "recipe/recipe.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::cli {

// How a recipe is run: the options `run` and `home` share.
struct RunArgs {
  bool emulate = false;
  bool virtual_time = false;
  std::string journal_dir;
  std::string state_dir;
  std::vector<std::string> faults_text;
  std::vector<runtime::FaultSpec> faults;  // parsed (and so checked) by the option's validator
  PageArgs page;                           // --http and its options
};

// --emulate, --virtual-time, --journal, --state-dir, --fault and the page's options on `sub`.
void add_run_options(CLI::App* sub, RunArgs& args);

// Runs a loaded recipe: banner, live status, operator console, the summary; its exit status.
// `run_dir` is the run record's folder.
[[nodiscard]] int run_loaded_recipe(const GlobalOptions& global, const config::CellConfig& cell,
                                    const recipe::Recipe& recipe, const RunArgs& args,
                                    const std::filesystem::path& run_dir);

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

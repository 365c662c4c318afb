#pragma once
// `cellctl run RECIPE`: runs a recipe on the cell — hardware, emulators in real time, or
// emulators in virtual time — with live status, a run record and a summary at the end.

#include <vector>

#include "cli/commands.hpp"
#include "config/cell_config.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::cli {

void add_run_command(CLI::App& app, Commands& commands);
// --fault's validator (run and teach-in): the text becomes a FaultSpec in `out`, or the reason is
// CLI11's error (exit 2).
[[nodiscard]] CLI::Validator fault_spec_validator(std::vector<runtime::FaultSpec>& out);
// Faults asked for where they cannot be rehearsed — a run that is not emulated, a device the cell lacks:
// said (logged), and true (then exit 2).
[[nodiscard]] bool refuse_faults(const std::vector<runtime::FaultSpec>& faults, bool emulated);
[[nodiscard]] bool refuse_faults(const std::vector<runtime::FaultSpec>& faults,
                                 const config::CellConfig& cell);

}  // namespace cellctl::cli

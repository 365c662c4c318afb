#pragma once
// `cellctl run RECIPE`: runs a recipe on the cell — hardware, emulators in real time, or
// emulators in virtual time — with live status, a run record and a summary at the end.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_run_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

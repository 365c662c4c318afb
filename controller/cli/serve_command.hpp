#pragma once
// `cellctl serve`: the controller standing by for the plant and the operator page (jobs/job_scheduler.hpp).
// It keeps the MQTT plant link and the page up between jobs and runs the recipes, homing and
// Teach-Ins they start, one at a time, each with its own run record.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_serve_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

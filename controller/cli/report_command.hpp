#pragma once
// `cellctl report RUN_DIR [--csv FILE]`: a run record summarised for an engineer, its samples exported.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_report_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

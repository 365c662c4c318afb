#pragma once
// `cellctl compare RUN_A RUN_B`: two runs of one recipe overlaid in one plot, per-step differences printed.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_compare_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

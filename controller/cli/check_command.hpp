#pragma once
// `cellctl check RECIPE…`: validates the cell config and each recipe against it, moves nothing.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_check_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

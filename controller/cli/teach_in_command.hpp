#pragma once
// `cellctl teach-in AXIS --distance MM`: the encoder's Teach-In (manual 4.4.2) as a guided routine —
// prerequisites switched on, the axis moved by the SCU (or by the operator with --manual), the result
// verified by moving back, then the total resolution written into the cell config (backup kept).

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_teach_in_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

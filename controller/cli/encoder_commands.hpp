#pragma once
// `cellctl encoder status|diag|preset|direction|set-address|teach-in`: commissioning the Scancon
// SCH88BEX over PROFIBUS DP (through its own DP master session), one command per run.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_encoder_commands(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

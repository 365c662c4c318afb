#pragma once
// `cellctl emulate`: the cell's devices as emulators on pseudo-terminals until Ctrl-C, so that any
// program (cellctl's commissioning commands, a terminal, a third-party master) talks to them as to
// hardware.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_emulate_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

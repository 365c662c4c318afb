#pragma once
// `cellctl scu status|move|stop`: commissioning of the SCU on its own, through the same scu::Session
// the controller uses. Every command opens remote mode, does its job and closes remote mode again
// (RS for anything it started, then RA), so the SCU is left in normal mode.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_scu_commands(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

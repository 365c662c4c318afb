#pragma once
// `cellctl spindle status|start|stop|set|reset`: commissioning of the spindle converter on its own,
// through the same spindle::Session the controller uses. `start` leaves the spindle running on exit
// (the converter has no RS232 watchdog); Ctrl-C during a command stops it.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_spindle_commands(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

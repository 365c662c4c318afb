#pragma once
// `cellctl home [AXIS…]`: homes the axes as the cell config's `homing:` says, after the operator has
// seen what will move and confirmed it (--yes for scripts). It runs a one-step recipe (`home: [...]`,
// written into the run record's folder as home.yaml) through the same path as `cellctl run`: the same
// modes, live status, operator commands, journal, plots and exit status; the home record is written
// at the end.

#include "cli/commands.hpp"

namespace cellctl::cli {

void add_home_command(CLI::App& app, Commands& commands);

}  // namespace cellctl::cli

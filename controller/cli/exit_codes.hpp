#pragma once
// The exit statuses moved down to exit_codes/ (the plant link and the job scheduler use them too).
// This forwarding header stays only for the files that still include it by this name (cell_standby.*,
// run_command.cpp, serve_command.cpp, edited by others while it moved); it goes when they include
// "exit_codes/exit_codes.hpp".
#include "exit_codes/exit_codes.hpp"

#pragma once
// Logging set-up for the cellctl process: the console logger and, when asked, the telegram trace
// logger "trace". Both are asynchronous so that nothing the control cycle logs waits on a terminal.

#include <string>

namespace cellctl::cli {

void init_logging(const std::string& level, bool trace);

}  // namespace cellctl::cli

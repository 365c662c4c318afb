#include "cli/operator_console.hpp"

#include <poll.h>
#include <unistd.h>

#include <string>

namespace cellctl::cli {

OperatorConsole::OperatorConsole(runtime::CellRun& run) : run_(run) {
  if (isatty(STDIN_FILENO)) thread_ = std::thread([this] { read_commands(); });
}

OperatorConsole::~OperatorConsole() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void OperatorConsole::read_commands() {
  std::string pending;
  while (!stop_.load()) {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;  // wakes up to notice the end of the run
    char buf[64];
    const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
    if (n <= 0) return;
    pending.append(buf, static_cast<std::size_t>(n));
    for (auto nl = pending.find('\n'); nl != std::string::npos; nl = pending.find('\n')) {
      const auto word = pending.substr(0, nl);
      pending.erase(0, nl + 1);
      using supervisor::Command;
      if (word == "hold" || word == "h") run_.request(Command::hold);
      if (word == "unhold" || word == "u") run_.request(Command::unhold);
      if (word == "stop" || word == "s") run_.request(Command::stop);
      if (word == "abort" || word == "a") run_.request(Command::abort);
      if (word == "reset" || word == "r") run_.request(Command::reset);
    }
  }
}

}  // namespace cellctl::cli

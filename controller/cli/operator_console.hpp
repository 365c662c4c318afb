#pragma once
// Operator commands typed during a run (hold, unhold, stop, abort, reset, clear; h/u/s/a/r/c; any
// case), read on their own thread and judged by the arbiter, as the page's and the plant's are. Every
// line typed gets an answer on the screen: a command the arbiter refuses, with its reason; one it
// passes on, with the run's answer (done, or refused and why) from the journal, see RunNarrator;
// anything else with what can be typed, and journaled.
// On a TTY (stdin and stdout) the terminal's echo is off and the console shows the typing after the
// status line itself, so typed text never glues onto it; Ctrl-C still reaches the run.

#include <termios.h>

#include <atomic>
#include <optional>
#include <string>
#include <thread>

#include "cli/terminal_screen.hpp"
#include "command/arbiter.hpp"
#include "runtime/cell_run.hpp"

namespace cellctl::cli {

class OperatorConsole {
 public:
  OperatorConsole(runtime::CellRun& run, command::Arbiter& arbiter, TerminalScreen& screen);
  ~OperatorConsole();  // restores the terminal
  OperatorConsole(const OperatorConsole&) = delete;
  OperatorConsole& operator=(const OperatorConsole&) = delete;

  [[nodiscard]] bool active() const noexcept { return thread_.joinable(); }

  // "hold", "HOLD", "h" → hold; nullopt for anything else.
  [[nodiscard]] static std::optional<supervisor::Command> parse(std::string_view word);

 private:
  void read_commands();
  void handle(const std::string& line);

  runtime::CellRun& run_;
  command::Arbiter& arbiter_;
  TerminalScreen& screen_;
  std::optional<termios> saved_;  // the terminal's settings before, when the console changed them
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cellctl::cli

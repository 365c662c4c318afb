#pragma once
// The run's terminal, shared by the status printer, the operator console and the run's messages:
// on a TTY one status line kept at the bottom, the operator's typing shown after it ("> hol"),
// messages printed above it — nothing glued onto anything. Piped (a log, CI): plain lines, no
// escape codes, no colour. Colour only on a TTY, and not when NO_COLOR is set or TERM is dumb.

#include <mutex>
#include <string>
#include <string_view>

namespace cellctl::cli {

class TerminalScreen {
 public:
  TerminalScreen();
  ~TerminalScreen();  // ends the status line
  TerminalScreen(const TerminalScreen&) = delete;
  TerminalScreen& operator=(const TerminalScreen&) = delete;

  [[nodiscard]] bool tty() const noexcept { return tty_; }
  [[nodiscard]] bool colour() const noexcept { return colour_; }

  // ANSI SGR colour around text when colour is on ("32" green, "33" yellow, "31" red, "1" bold).
  [[nodiscard]] std::string paint(std::string_view sgr, std::string_view text) const;

  // TTY: replaces the status line. Piped: prints it as a line.
  void status(const std::string& line);
  // A line above the status line (or just a line, piped).
  void message(const std::string& text);
  // What the operator has typed so far (TTY only; shown after the status line).
  void typing(const std::string& text);

 private:
  void redraw_locked();

  std::mutex mutex_;
  bool tty_;
  bool colour_;
  std::string status_;
  std::string typed_;
  bool typing_ = false;
};

}  // namespace cellctl::cli

#include "cli/terminal_screen.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace cellctl::cli {
namespace {

bool wants_colour(bool tty) {
  const char* term = std::getenv("TERM");
  return tty && std::getenv("NO_COLOR") == nullptr && term != nullptr && std::strcmp(term, "dumb") != 0;
}

}  // namespace

TerminalScreen::TerminalScreen() : tty_(isatty(STDOUT_FILENO) != 0), colour_(wants_colour(tty_)) {}

TerminalScreen::~TerminalScreen() {
  const std::lock_guard lock(mutex_);
  if (tty_ && !status_.empty()) {
    fmt::print("\r\033[K{}\n", status_);
    std::fflush(stdout);
  }
}

std::string TerminalScreen::paint(std::string_view sgr, std::string_view text) const {
  if (!colour_) return std::string(text);
  return fmt::format("\033[{}m{}\033[0m", sgr, text);
}

void TerminalScreen::redraw_locked() {
  fmt::print("\r\033[K{}", status_);
  if (typing_) fmt::print("  {} {}", colour_ ? "\033[1m>\033[0m" : ">", typed_);
  std::fflush(stdout);
}

void TerminalScreen::status(const std::string& line) {
  const std::lock_guard lock(mutex_);
  status_ = line;
  if (tty_)
    redraw_locked();
  else {
    fmt::print("{}\n", line);
    std::fflush(stdout);
  }
}

void TerminalScreen::message(const std::string& text) {
  const std::lock_guard lock(mutex_);
  if (tty_) {
    fmt::print("\r\033[K{}\n", text);
    redraw_locked();
  } else {
    fmt::print("{}\n", text);
    std::fflush(stdout);
  }
}

void TerminalScreen::typing(const std::string& text) {
  const std::lock_guard lock(mutex_);
  typed_ = text;
  typing_ = !text.empty();
  if (tty_) redraw_locked();
}

}  // namespace cellctl::cli

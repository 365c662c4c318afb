#include "cli/operator_console.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <string>

namespace cellctl::cli {
namespace {

constexpr std::string_view kWhatToType =
    "type hold, unhold, stop, abort, reset or clear (or h, u, s, a, r, c) and Enter";

std::string trimmed_lower(std::string_view word) {
  while (!word.empty() && std::isspace(static_cast<unsigned char>(word.front()))) word.remove_prefix(1);
  while (!word.empty() && std::isspace(static_cast<unsigned char>(word.back()))) word.remove_suffix(1);
  std::string out(word);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

}  // namespace

std::optional<supervisor::Command> OperatorConsole::parse(std::string_view word) {
  using supervisor::Command;
  const auto w = trimmed_lower(word);
  if (w == "hold" || w == "h") return Command::hold;
  if (w == "unhold" || w == "u") return Command::unhold;
  if (w == "stop" || w == "s") return Command::stop;
  if (w == "abort" || w == "a") return Command::abort;
  if (w == "reset" || w == "r") return Command::reset;
  if (w == "clear" || w == "c") return Command::clear;
  return std::nullopt;
}

OperatorConsole::OperatorConsole(runtime::CellRun& run, command::Arbiter& arbiter, TerminalScreen& screen)
    : run_(run), arbiter_(arbiter), screen_(screen) {
  if (!isatty(STDIN_FILENO)) return;
  if (screen_.tty()) {
    termios t{};
    if (tcgetattr(STDIN_FILENO, &t) == 0) {
      saved_ = t;
      t.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);  // ISIG stays: Ctrl-C is still the operator stop
      t.c_cc[VMIN] = 1;
      t.c_cc[VTIME] = 0;
      tcsetattr(STDIN_FILENO, TCSANOW, &t);
    }
  }
  thread_ = std::thread([this] { read_commands(); });
}

OperatorConsole::~OperatorConsole() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  if (saved_) tcsetattr(STDIN_FILENO, TCSANOW, &*saved_);
}

void OperatorConsole::handle(const std::string& line) {
  if (trimmed_lower(line).empty()) {
    run_.confirm();  // Enter: a manual Teach-In's "moved as asked" (nothing else waits for it)
    return;
  }
  const auto cmd = parse(line);
  if (!cmd) {
    screen_.message(fmt::format("'{}' is not a command: {}", line, kWhatToType));
    run_.note_from_operator(fmt::format("operator typed '{}': not a command, ignored", line));
    return;
  }
  const auto name = supervisor::to_string(*cmd);
  if (trimmed_lower(line) != name)
    screen_.message(fmt::format("> {}: taken as '{}'", line, name));
  else
    screen_.message(fmt::format("> {}", name));
  // Judged by the arbiter, as the page's and the plant's; a run's answer comes from the journal
  // (RunNarrator).
  const auto taken = arbiter_.command(
      *cmd, {{command::CommandSource::Origin::terminal, {}, {}}, std::chrono::steady_clock::now(), {}});
  if (taken.how != command::Taken::How::by_run) screen_.message(fmt::format("  {}", taken.text));
}

void OperatorConsole::read_commands() {
  std::string pending;
  while (!stop_.load()) {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;  // wakes up to notice the end of the run
    char buf[64];
    const ssize_t n = ::read(STDIN_FILENO, buf, sizeof buf);
    if (n <= 0) return;
    for (ssize_t i = 0; i < n; ++i) {
      const char c = buf[i];
      if (c == '\n' || c == '\r') {
        const auto line = pending;
        pending.clear();
        screen_.typing({});
        handle(line);
      } else if (c == 0x7f || c == '\b') {
        if (!pending.empty()) pending.pop_back();
        screen_.typing(pending);
      } else if (std::isprint(static_cast<unsigned char>(c)) && pending.size() < 60) {
        pending.push_back(c);
        screen_.typing(pending);
      }
    }
  }
}

}  // namespace cellctl::cli

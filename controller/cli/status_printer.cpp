#include "cli/status_printer.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace cellctl::cli {
namespace {

std::string line(const runtime::StatusView& v, const config::CellConfig& cell) {
  std::string s =
      fmt::format("[{:7.1f} s] {:<10} step {}/{}", v.t, supervisor::to_string(v.state), v.step, v.steps);
  if (!v.label.empty()) s += fmt::format(" {}", v.label);
  s += " |";
  for (std::size_t i = 0; i < v.axes && i < cell.axes.size(); ++i)
    s += fmt::format(" {} {:7.2f}", cell.axes[i].name, v.position_mm[i]);
  s += fmt::format(" mm | spindle {:4.0f} Hz", v.spindle_hz);
  if (v.fault) s += fmt::format(" | FAULT {}", monitor::to_string(v.first_fault));
  return s;
}

}  // namespace

StatusPrinter::StatusPrinter(const runtime::StatusBoard& board, const config::CellConfig& cell)
    : board_(board), cell_(cell), tty_(isatty(STDOUT_FILENO) != 0), thread_([this] { run(); }) {}

StatusPrinter::~StatusPrinter() {
  stop_.store(true);
  thread_.join();
}

void StatusPrinter::run() {
  using clock = std::chrono::steady_clock;
  auto last_plain = clock::now();
  runtime::StatusView last{};
  bool first = true;
  while (!stop_.load()) {
    const auto v = board_.read();
    if (tty_) {
      fmt::print("\r\033[K{}", line(v, cell_));
      std::fflush(stdout);
    } else {
      const bool changed = first || v.state != last.state || v.step != last.step || v.fault != last.fault;
      if (changed || clock::now() - last_plain > std::chrono::seconds(5)) {
        fmt::print("{}\n", line(v, cell_));
        std::fflush(stdout);
        last_plain = clock::now();
      }
    }
    last = v;
    first = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(tty_ ? 100 : 50));
  }
  const auto v = board_.read();
  if (tty_) fmt::print("\r\033[K");
  fmt::print("{}\n", line(v, cell_));
  std::fflush(stdout);
}

}  // namespace cellctl::cli

#include "cli/status_printer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <string>

namespace cellctl::cli {
namespace {

std::string_view state_colour(supervisor::State s) {
  using supervisor::State;
  switch (s) {
    case State::execute:
    case State::complete:
    case State::completing:
      return "32";
    case State::holding:
    case State::held:
    case State::unholding:
      return "33";
    case State::stopping:
    case State::stopped:
    case State::aborting:
    case State::aborted:
      return "31";
    default:
      return "0";
  }
}

}  // namespace

StatusPrinter::StatusPrinter(const status::StatusBoard& board, const config::CellConfig& cell,
                             TerminalScreen& screen, std::vector<std::optional<double>> planned_s)
    : board_(board), cell_(cell), screen_(screen), planned_s_(std::move(planned_s)), thread_([this] {
        run();
      }) {}

StatusPrinter::~StatusPrinter() {
  stop_.store(true);
  thread_.join();
}

std::string StatusPrinter::line(const status::StatusView& v) {
  std::string s = fmt::format("[{:7.1f} s] ", v.t);
  if (v.state == supervisor::State::idle && v.steps == 0) {
    // Before the first cycle: the devices are being opened.
    return s + fmt::format("starting: opening the devices, {} steps to run", planned_s_.size());
  }
  s += screen_.paint(state_colour(v.state), fmt::format("{:<10}", supervisor::to_string(v.state)));
  if (v.step != shown_step_) shown_step_ = v.step, step_since_ = v.t;
  if (v.step > 0) {
    s += fmt::format(" step {}/{}", v.step, v.steps);
    if (!v.label.empty()) s += fmt::format(" {}", v.label);
    // The step's time while it runs (a held or ended step's clock says nothing).
    const double in_step = v.t - step_since_;
    auto planned = v.step <= planned_s_.size() ? planned_s_[v.step - 1] : std::nullopt;
    if (!planned && v.step_planned_s > 0.0) planned = v.step_planned_s;  // a move's, once it started
    if (v.state == supervisor::State::execute) {
      s += planned && *planned > 0.0
               ? fmt::format(" · {:.1f} of {:.1f} s", std::min(in_step, *planned), *planned)
               : fmt::format(" · {:.1f} s", in_step);
    }
  }
  s += " |";
  for (std::size_t i = 0; i < v.axes && i < cell_.axes.size(); ++i)
    s += v.position_known[i] ? fmt::format(" {} {:7.2f}", cell_.axes[i].name, v.position_mm[i])
                             : fmt::format(" {}      —", cell_.axes[i].name);
  s += fmt::format(" mm | spindle {:.0f} Hz", v.spindle_hz);
  if (v.spindle_set_hz > 0.0 || v.spindle_hz > 0.5) s += fmt::format(" (set {:.0f})", v.spindle_set_hz);
  if (v.fault) s += " | " + screen_.paint("1;31", fmt::format("FAULT {}", monitor::to_string(v.first_fault)));
  return s;
}

void StatusPrinter::run() {
  using clock = std::chrono::steady_clock;
  auto last_plain = clock::now();
  status::StatusView last{};
  bool first = true;
  while (!stop_.load()) {
    const auto v = board_.read();
    const bool changed = first || v.state != last.state || v.step != last.step || v.fault != last.fault;
    if (screen_.tty() || changed || clock::now() - last_plain > std::chrono::seconds(5)) {
      screen_.status(line(v));
      last_plain = clock::now();
    }
    last = v;
    first = false;
    std::this_thread::sleep_for(std::chrono::milliseconds(screen_.tty() ? 100 : 50));
  }
  // The last status stays on the screen; piped, only if it says something the last line did not.
  const auto v = board_.read();
  if (screen_.tty() || v.state != last.state || v.step != last.step || v.fault != last.fault)
    screen_.status(line(v));
}

}  // namespace cellctl::cli

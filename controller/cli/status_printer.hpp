#pragma once
// The live status of a run, from its own thread, on the TerminalScreen: on a TTY one line rewritten
// a few times a second; piped, a plain line whenever the step or state changes and every few
// seconds, so the log reads as a history. Meaningful from the first moment: before the first cycle
// it says what it is waiting for, and positions not yet reported show as "—".
//
//   [  12.3 s] Execute   step 5/25 drill hole 1 1/2 › dwell at depth (line 29) 0.3 of 0.5 s
//              | x  30.00  z  60.00 mm | spindle 400 Hz (set 400)

#include <atomic>
#include <optional>
#include <thread>
#include <vector>

#include "cli/terminal_screen.hpp"
#include "config/cell_config.hpp"
#include "status/status_view.hpp"

namespace cellctl::cli {

class StatusPrinter {
 public:
  // `planned_s`: per step (as numbered by the run), its planned time where it is known before.
  StatusPrinter(const status::StatusBoard& board, const config::CellConfig& cell, TerminalScreen& screen,
                std::vector<std::optional<double>> planned_s);
  ~StatusPrinter();  // stops and prints the last status
  StatusPrinter(const StatusPrinter&) = delete;
  StatusPrinter& operator=(const StatusPrinter&) = delete;

 private:
  void run();
  [[nodiscard]] std::string line(const status::StatusView& v);

  const status::StatusBoard& board_;
  const config::CellConfig& cell_;
  TerminalScreen& screen_;
  std::vector<std::optional<double>> planned_s_;
  std::uint32_t shown_step_ = 0;
  double step_since_ = 0.0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cellctl::cli

#pragma once
// The live status of a run on the terminal, from its own thread: on a TTY one line rewritten in
// place a few times a second; otherwise (a log, CI) a plain line whenever the step or state changes
// and every few seconds, so the log reads as a history.

#include <atomic>
#include <thread>

#include "config/cell_config.hpp"
#include "runtime/status_view.hpp"

namespace cellctl::cli {

class StatusPrinter {
 public:
  StatusPrinter(const runtime::StatusBoard& board, const config::CellConfig& cell);
  ~StatusPrinter();  // stops and ends the line
  StatusPrinter(const StatusPrinter&) = delete;
  StatusPrinter& operator=(const StatusPrinter&) = delete;

 private:
  void run();

  const runtime::StatusBoard& board_;
  const config::CellConfig& cell_;
  bool tty_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cellctl::cli

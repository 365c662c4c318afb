#pragma once
// Operator commands typed during a run (hold, unhold, stop, abort, reset), read from the terminal
// on their own thread and handed to the run; only when stdin is a terminal.

#include <atomic>
#include <thread>

#include "runtime/cell_run.hpp"

namespace cellctl::cli {

class OperatorConsole {
 public:
  explicit OperatorConsole(runtime::CellRun& run);
  ~OperatorConsole();
  OperatorConsole(const OperatorConsole&) = delete;
  OperatorConsole& operator=(const OperatorConsole&) = delete;

  [[nodiscard]] bool active() const noexcept { return thread_.joinable(); }

 private:
  void read_commands();

  runtime::CellRun& run_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cellctl::cli

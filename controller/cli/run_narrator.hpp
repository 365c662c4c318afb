#pragma once
// Says on the screen what the run records, as it is recorded: the answer to every typed command
// (done, or refused and why, and what to type next), faults (and what Ctrl-C's hold expects next),
// state changes, failed steps, device notes. Fed from the journal's writer thread
// (CellRun::on_journal_line), so what the operator reads is what the record holds.

#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/terminal_screen.hpp"

namespace cellctl::cli {

class RunNarrator {
 public:
  explicit RunNarrator(TerminalScreen& screen) : screen_(screen) {}
  void operator()(const nlohmann::json& line);

 private:
  [[nodiscard]] std::string next_step_hint() const;

  TerminalScreen& screen_;
  std::string state_ = "Idle";
};

}  // namespace cellctl::cli

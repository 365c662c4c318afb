#pragma once
// Says on the screen what the run records, as it is recorded: the answer to every typed command
// (done, or refused and why, and what to type next), faults (and what Ctrl-C's hold expects next),
// state changes, failed steps, device notes. It listens to the run's journal (CellRun::listen), so what
// the operator reads is what the record holds.

#include <string>
#include <string_view>

#include "cli/terminal_screen.hpp"
#include "journal/event_listener.hpp"

namespace cellctl::cli {

class RunNarrator final : public journal::EventListener {
 public:
  explicit RunNarrator(TerminalScreen& screen) : screen_(screen) {}
  void on_event(const journal::Event& e) override;
  void on_note(double t, std::string_view text) override;

 private:
  [[nodiscard]] std::string next_step_hint() const;

  TerminalScreen& screen_;
  std::string state_ = "Idle";
};

}  // namespace cellctl::cli

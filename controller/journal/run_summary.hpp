#pragma once
// What a run amounted to, for the terminal and the journal's closing line: time spent per step
// (repeated steps added up, a step's time before and during a hold kept, a step a stop interrupted
// included), the faults, how it ended. Built on the RunRecord the journal fills as it writes.

#include <string>
#include <string_view>
#include <vector>

#include "journal/event.hpp"
#include "journal/run_record.hpp"
#include "schema/summary_line.hpp"

namespace cellctl::journal {

class RunSummary {
 public:
  // As RunRecord::add and add_note.
  void add(const Event& e) { record_.add(e); }
  void add_note(double t, std::string_view text) { record_.add_note(t, text); }

  using StepTime = schema::StepTime;
  [[nodiscard]] std::vector<StepTime> steps() const;
  // "4.000s overspeed (category 1): x at 30.0 mm/s", in order; injected faults too.
  [[nodiscard]] std::vector<std::string> faults() const;
  [[nodiscard]] const std::string& outcome() const noexcept { return record_.outcome(); }
  [[nodiscard]] double duration_s() const noexcept { return record_.duration_s(); }
  [[nodiscard]] const RunRecord& record() const noexcept { return record_; }
  [[nodiscard]] RunRecord& record() noexcept { return record_; }

  // The summary line's own part (outcome, duration, steps, faults); the journal and the run add theirs.
  [[nodiscard]] schema::SummaryLine line() const;
  // A few lines for the terminal.
  [[nodiscard]] std::string to_text() const;

 private:
  RunRecord record_;
};

}  // namespace cellctl::journal

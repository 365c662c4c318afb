#pragma once
// What a run amounted to, for the terminal and the journal's closing line: time spent per step
// (repeated steps added up, a step's time before and during a hold kept, a step a stop interrupted
// included), the faults, how it ended. Built on the RunRecord the journal fills as it writes.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "journal/event.hpp"
#include "journal/run_record.hpp"

namespace cellctl::journal {

class RunSummary {
 public:
  void add(const Event& e);
  void add(const nlohmann::json& line) { record_.add(line); }

  struct StepTime {
    std::string label;
    int count = 0;
    double seconds = 0.0;
    int failed = 0;
    int interrupted = 0;
    double held_s = 0.0;
  };
  [[nodiscard]] std::vector<StepTime> steps() const;
  // "4.000s overspeed (category 1): x at 30.0 mm/s", in order; injected faults too.
  [[nodiscard]] std::vector<std::string> faults() const;
  [[nodiscard]] const std::string& outcome() const noexcept { return record_.outcome(); }
  [[nodiscard]] double duration_s() const noexcept { return record_.duration_s(); }
  [[nodiscard]] const RunRecord& record() const noexcept { return record_; }
  [[nodiscard]] RunRecord& record() noexcept { return record_; }

  [[nodiscard]] nlohmann::json to_json() const;
  // A few lines for the terminal.
  [[nodiscard]] std::string to_text() const;

 private:
  RunRecord record_;
};

// Seconds, milliseconds kept: 1.27 rather than 1.2700000000000005 in JSON.
[[nodiscard]] double round_ms(double seconds) noexcept;

}  // namespace cellctl::journal

#pragma once
// What a run amounted to, built from its events: time spent per step (repeated steps added up),
// the faults, how it ended. Lives on the journal's writer thread.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "journal/event.hpp"

namespace cellctl::journal {

class RunSummary {
 public:
  void add(const Event& e);

  struct StepTime {
    std::string label;
    int count = 0;
    double seconds = 0.0;
    int failed = 0;
  };
  [[nodiscard]] const std::vector<StepTime>& steps() const noexcept { return steps_; }
  [[nodiscard]] const std::vector<std::string>& faults() const noexcept { return faults_; }
  [[nodiscard]] const std::string& outcome() const noexcept { return outcome_; }
  [[nodiscard]] double duration_s() const noexcept { return end_ - start_; }

  [[nodiscard]] nlohmann::json to_json() const;
  // A few lines for the terminal.
  [[nodiscard]] std::string to_text() const;

 private:
  std::vector<StepTime> steps_;  // in order of first appearance
  std::map<std::string, std::size_t> by_label_;
  std::map<std::uint32_t, double> open_;  // step index → start time
  std::vector<std::string> faults_;
  std::string outcome_ = "unfinished";
  double start_ = 0.0;
  double end_ = 0.0;
};

}  // namespace cellctl::journal

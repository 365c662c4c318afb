#pragma once
// A job's end state is told only once its work is saved (issue 22, "an end state means the work is
// saved"): the run's journal lines go on to the plant link and the page as they are written, except
// the state line into Complete, Stopped or Aborted, which waits until the job has written what it
// writes — the journal's summary (the run has ended), the home record, a taught config — and then goes
// on with what the job did appended to its reason. A plant that starts the next job on Complete so
// finds the home record and the taught resolution on disk.

#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

namespace cellctl::cli {

class EndStateGate {
 public:
  using Listener = std::function<void(const nlohmann::json&)>;
  explicit EndStateGate(Listener next) : next_(std::move(next)) {}

  // The run's journal listener (on the journal's thread).
  void operator()(const nlohmann::json& line) {
    {
      const std::lock_guard lock(mutex_);
      if (is_end(line)) {
        held_ = line;
        return;
      }
    }
    if (next_) next_(line);
  }

  // Once the job's work is on disk: the held end state goes on, `words` appended to its reason. A run
  // that never reached an end state (it could not start) has nothing held.
  void release(const std::string& words = {}) {
    const auto line = take(words);
    if (line && next_) next_(*line);
  }
  // The held end state with `words` appended to its reason, for the caller to tell when it is ready
  // for what the line will bring (serve: once it takes the next command); none when nothing is held.
  [[nodiscard]] std::optional<nlohmann::json> take(const std::string& words = {}) {
    std::optional<nlohmann::json> line;
    {
      const std::lock_guard lock(mutex_);
      line.swap(held_);
    }
    if (line && !words.empty()) (*line)["reason"] = line->value("reason", std::string()) + "; " + words;
    return line;
  }

 private:
  static bool is_end(const nlohmann::json& line) {
    if (line.value("event", "") != "state") return false;
    const auto to = line.value("to", "");
    return to == "Complete" || to == "Stopped" || to == "Aborted";
  }

  Listener next_;
  std::mutex mutex_;
  std::optional<nlohmann::json> held_;
};

}  // namespace cellctl::cli

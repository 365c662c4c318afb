#pragma once
// Commands from outside the terminal (the plant over MQTT, the web page), put through the operator's
// one command path (runtime::CellRun::request, as the terminal's) and answered with the outcome the
// run gives: accepted, or refused and why (the supervisor's and the monitor's own reasons, read from
// the run's events, as the terminal's narrator reads them). A command the current state does not
// allow is refused by the run at once, never queued. `start` names a recipe in the recipe folder: it
// is validated first (every problem file:line:column, as `cellctl check` and exit 3 give them); this
// cellctl drives one run, so a valid start is refused while that run exists.
// Used on one thread (the link's or the web server's).

#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/run_event.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::plant_link {

using SteadyTime = std::chrono::steady_clock::time_point;

class CommandDesk {
 public:
  // `request` is the run's operator command path; empty when there is no run to command.
  CommandDesk(const config::CellCore& cell, std::filesystem::path recipes,
              std::function<void(supervisor::Command)> request, std::chrono::milliseconds answer_timeout);

  // `word` is the command (hold, unhold, stop, abort, reset, start); `payload` empty or JSON
  // {"id":…, "recipe":…}; `source` says who sent it (for the answer). Returns the answer when it is
  // known at once (a refusal, a start's validation), nullopt when the run will answer (on_event).
  [[nodiscard]] std::optional<nlohmann::json> submit(std::string_view word, std::string_view payload,
                                                     std::string_view source, std::string_view state,
                                                     SteadyTime now);
  // The answers this run event completes.
  [[nodiscard]] std::vector<nlohmann::json> on_event(const RunEvent& e);
  // Answers for commands the run has not answered within the time-out.
  [[nodiscard]] std::vector<nlohmann::json> expire(SteadyTime now);
  [[nodiscard]] bool waiting() const noexcept { return !pending_.empty(); }

 private:
  struct Pending {
    supervisor::Command command;
    nlohmann::json id;
    std::string source;
    SteadyTime deadline;
  };
  [[nodiscard]] nlohmann::json validate_start(const nlohmann::json& id, const std::string& recipe,
                                              std::string_view state) const;

  const config::CellCore& cell_;
  std::filesystem::path recipes_;
  std::function<void(supervisor::Command)> request_;
  std::chrono::milliseconds timeout_;
  std::deque<Pending> pending_;
};

// An answer: {"command", "id" (when given), "ok", "outcome" or "reason", more fields as given}.
[[nodiscard]] nlohmann::json answer(std::string_view command, const nlohmann::json& id, bool ok,
                                    std::string text);

}  // namespace cellctl::plant_link

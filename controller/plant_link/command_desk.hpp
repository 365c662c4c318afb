#pragma once
// Commands from outside the terminal (the plant over MQTT, the web page), put through the operator's
// one command path (runtime::CellRun::request, as the terminal's) and answered with the outcome the
// run gives: accepted, or refused and why (the supervisor's and the monitor's own reasons, read from
// the run's events, as the terminal's narrator reads them). A command the current state does not
// allow is refused by the run at once, never queued.
// Starts: `start` names a recipe in the recipe folder, validated first (every problem
// file:line:column, as `cellctl check` and exit 3 give them); `home` ({"axes":[…]}, or every axis with
// homing) and `teach-in` ({"axis","distance_mm", optional "from_mm", "speed_mm_s"}) start the cell's
// routines. A standing controller (cellctl serve, RunAccess::start) starts them when no job is in
// progress; `cellctl run` drives one run, so it refuses them with the reason.
// Used on one thread (the link's or the web server's).

#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/run_access.hpp"
#include "plant_link/run_event.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::plant_link {

using SteadyTime = std::chrono::steady_clock::time_point;

class CommandDesk {
 public:
  // `access`: the operator command path and the starts (run_access.hpp); its request may be empty
  // when there is no run to command.
  CommandDesk(const config::CellCore& cell, std::filesystem::path recipes, RunAccess access,
              std::chrono::milliseconds answer_timeout);

  // `word` is the command (hold, unhold, stop, abort, reset, start, home, teach-in); `payload` empty
  // or a JSON object ({"id":…} and the start's fields); `source` says who sent it (for the answer).
  // Returns the answer when it is known at once (a refusal, a start), nullopt when the run will
  // answer (on_event).
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
  // The start of a recipe, homing or a Teach-In: its shape checked, then started (or refused).
  [[nodiscard]] nlohmann::json start(std::string_view word, const nlohmann::json& id,
                                     const nlohmann::json& body, std::string_view state) const;
  // A recipe's StartRequest, or the answer that refuses it (not a name, not valid for the cell).
  [[nodiscard]] std::variant<StartRequest, nlohmann::json> recipe_start(const nlohmann::json& id,
                                                                        const nlohmann::json& body) const;

  const config::CellCore& cell_;
  std::filesystem::path recipes_;
  RunAccess access_;
  std::chrono::milliseconds timeout_;
  std::deque<Pending> pending_;
};

// An answer: {"command", "id" (when given), "ok", "outcome" or "reason", more fields as given}.
[[nodiscard]] nlohmann::json answer(std::string_view command, const nlohmann::json& id, bool ok,
                                    std::string text);

}  // namespace cellctl::plant_link

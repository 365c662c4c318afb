#pragma once
// Commands from outside the terminal (the plant over MQTT, the web page): bounded and parsed here,
// then judged by the one arbiter (command/arbiter.hpp: age, PackML interlocks) and answered with the
// outcome: accepted, or refused and why (the arbiter's, the supervisor's and the monitor's own
// reasons, read from the run's events, as the terminal's narrator reads them). A command the current
// state does not allow is refused at once, never queued.
// A payload is empty or a JSON object of at most 64 KiB and 32 levels, read at the edge into typed
// fields (schema/command_payload.hpp); its optional fields: "id" (echoed), "issued_at" (UTC, RFC
// 3339: the command is judged by its age from then), "by" (who, recorded with the source). Answers are
// typed (schema/command_answer.hpp) and made JSON by whoever sends them.
// Starts: `start` names a recipe in the recipe folder, validated first (every problem
// file:line:column, as `cellctl check` and exit 3 give them) — but only once the arbiter has said a
// start would be taken now, so a flood of starts costs a comparison each; `home` ({"axes":[…]}, or
// every axis with homing) and `teach-in` ({"axis","distance_mm", optional "from_mm", "speed_mm_s"})
// start the cell's routines. A standing controller (cellctl serve, RunAccess::start) starts them in
// Idle; `cellctl run` drives one run, so it refuses them with the reason.
// Thread-safe: the page's workers and the link's thread may call it at once, and no call waits
// behind another's recipe validation.

#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "command/order.hpp"
#include "config/cell_core.hpp"
#include "plant_link/run_access.hpp"
#include "plant_link/run_event.hpp"
#include "schema/command_answer.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::plant_link {

using command::SteadyTime;
using schema::AnswerId;
using schema::CommandAnswer;

// A command as it arrived: its word, its payload as received (unparsed), who sent it and when.
struct Incoming {
  std::string_view word;  // hold, unhold, stop, abort, reset, clear, start, home, teach-in
  std::string_view payload;
  command::CommandSource source;
  SteadyTime received{};
  std::optional<std::uint64_t> id;  // the caller's own id for the answer (the page's), not the payload's
};

class CommandDesk {
 public:
  // `access`: the arbiter and the starts (run_access.hpp).
  CommandDesk(const config::CellCore& cell, std::filesystem::path recipes, RunAccess access,
              std::chrono::milliseconds answer_timeout);

  // Returns the answer when it is known at once (a refusal, a start), nullopt when the run will
  // answer (on_event). `state`: the cell's state as the caller shows it, for the answer's words.
  [[nodiscard]] std::optional<CommandAnswer> submit(const Incoming& in, std::string_view state);
  // The answers this run event completes.
  [[nodiscard]] std::vector<CommandAnswer> on_event(const RunEvent& e);
  // Answers for commands the run has not answered within the time-out.
  [[nodiscard]] std::vector<CommandAnswer> expire(SteadyTime now);
  [[nodiscard]] bool waiting() {
    const std::lock_guard lock(mutex_);
    return !pending_.empty();
  }

 private:
  struct Pending {
    supervisor::Command command;
    AnswerId id;
    std::string source;
    SteadyTime deadline;
  };
  // The start of a recipe, homing or a Teach-In: the arbiter asked first, its shape checked, then
  // started (or refused).
  [[nodiscard]] CommandAnswer start(std::string_view word, const AnswerId& id,
                                    const schema::CommandPayload& body, const command::Order& order,
                                    std::string_view state) const;
  // A recipe's StartRequest, or the answer that refuses it (not a name, not valid for the cell).
  [[nodiscard]] std::variant<StartRequest, CommandAnswer> recipe_start(
      const AnswerId& id, const schema::CommandPayload& body) const;

  const config::CellCore& cell_;
  std::filesystem::path recipes_;
  RunAccess access_;
  std::chrono::milliseconds timeout_;
  std::mutex mutex_;  // pending_
  std::deque<Pending> pending_;
};

// An answer to `command`: taken (ok, its outcome) or refused (its reason); the rest as the caller adds.
[[nodiscard]] CommandAnswer answer(std::string_view command, AnswerId id, bool ok, std::string text);

}  // namespace cellctl::plant_link

#include "cli/run_narrator.hpp"

#include <fmt/format.h>

#include "journal/run_record.hpp"

namespace cellctl::cli {
namespace {

bool contains(const std::string& s, std::string_view part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

std::string RunNarrator::next_step_hint() const {
  if (state_ == "Held" || state_ == "Holding") return "type unhold to go on, or stop to end";
  if (state_ == "Execute" || state_ == "Starting" || state_ == "Unholding") return "type hold or stop";
  if (state_ == "Stopped" || state_ == "Aborted" || state_ == "Complete") return "the run has ended";
  return "wait for the cell to come to rest";
}

void RunNarrator::operator()(const nlohmann::json& j) {
  const auto event = j.value("event", std::string());
  const double t = j.value("t", 0.0);
  const auto at = fmt::format("[{:7.1f} s]", t);
  if (event == "state") {
    state_ = j.value("to", state_);
    screen_.message(fmt::format("{} {} → {}{}", at, j.value("from", "?"), state_,
                                j.contains("reason") ? fmt::format(" ({})", j.value("reason", "")) : ""));
  } else if (event == "command" && j.value("command", "") != "start") {  // not the run's own start
    const auto cmd = j.value("command", "?");
    const auto source = j.value("source", "");
    const char* what = cmd == "hold"
                           ? "the cell comes to rest and holds; type unhold to go on, or stop to end"
                       : cmd == "unhold" ? "checking the latched faults: Unholding follows, or a refusal"
                       : cmd == "stop"   ? "the cell comes to a controlled stop and the run ends"
                       : cmd == "abort"  ? "the cell stops at once and the run ends"
                                         : "done";
    // An unhold is judged after it is journaled (a latched fault refuses it): received, not accepted.
    // From the page or the plant: whose it was, so that the operator at the terminal knows.
    const auto by =
        source == "terminal" || source.empty() ? std::string() : fmt::format(" (from {})", source);
    screen_.message(
        fmt::format("{} {}{}: {} — {}", at, cmd, by, cmd == "unhold" ? "received" : "accepted", what));
  } else if (event == "note") {
    const auto text = j.value("text", "");
    if (contains(text, "operator typed")) return;  // the console has answered it
    if (contains(text, "faults reset")) {
      screen_.message(fmt::format("{} reset: done, faults cleared — {}", at, next_step_hint()));
    } else if (contains(text, "reset refused")) {
      screen_.message(fmt::format("{} {} — remove the cause, then type reset again", at,
                                  screen_.paint("33", "refused: " + text)));
    } else if (contains(text, "unhold refused")) {
      screen_.message(
          fmt::format("{} {} — type reset, then unhold", at, screen_.paint("33", "refused: " + text)));
    } else if (contains(text, "not possible")) {
      screen_.message(
          fmt::format("{} {} — {}", at, screen_.paint("33", "refused: " + text), next_step_hint()));
    } else {
      screen_.message(fmt::format("{} note: {}", at, text));
    }
  } else if (event == "fault") {
    const auto rule = j.value("rule", "?");
    const int category = j.value("category", 1);
    screen_.message(fmt::format("{} {}", at,
                                screen_.paint("1;31", fmt::format("FAULT {} (stop category {}): {}", rule,
                                                                  category, j.value("detail", "")))));
    if (rule == "operator_stop" && category == 2)
      screen_.message(
          "           Ctrl-C: the cell holds — type `stop` to end, or `reset` then `unhold` to go on; Ctrl-C "
          "again "
          "is an emergency stop");
    else if (category == 2)
      screen_.message("           the cell holds — type `reset` then `unhold` to go on, or `stop` to end");
    else
      screen_.message(fmt::format("           the run stops (category {})", category));
  } else if (event == "fault_cleared") {
    screen_.message(fmt::format("{} fault cleared: {}", at, j.value("rule", "?")));
  } else if (event == "step_failed") {
    screen_.message(
        fmt::format("{} {}", at,
                    screen_.paint("31", fmt::format("step {} failed: {} — {}", j.value("step", 0),
                                                    j.value("label", ""), j.value("detail", "")))));
  } else if (event.find("inject") != std::string::npos) {
    screen_.message(
        fmt::format("{} {}", at, screen_.paint("35", "injected fault: " + journal::describe_event(j))));
  }
}

}  // namespace cellctl::cli

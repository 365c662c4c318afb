#include "cli/run_narrator.hpp"

#include <fmt/format.h>

#include "journal/run_record.hpp"

namespace cellctl::cli {
namespace {

bool contains(std::string_view s, std::string_view part) {
  return s.find(part) != std::string_view::npos;
}

std::string at(double t) {
  return fmt::format("[{:7.1f} s]", t);
}

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

std::string RunNarrator::next_step_hint() const {
  if (state_ == "Held" || state_ == "Holding") return "type unhold to go on, or stop to end";
  if (state_ == "Execute" || state_ == "Starting" || state_ == "Unholding") return "type hold or stop";
  if (state_ == "Stopped" || state_ == "Aborted" || state_ == "Complete") return "the run has ended";
  return "wait for the cell to come to rest";
}

void RunNarrator::on_event(const journal::Event& e) {
  std::visit(Overloaded{
                 [&](const journal::StateChanged& s) {
                   state_ = std::string(s.to);
                   screen_.message(fmt::format("{} {} → {}{}", at(e.t), s.from, state_,
                                               s.reason.size ? fmt::format(" ({})", s.reason.view()) : ""));
                 },
                 [&](const journal::Command& c) {
                   if (c.name == "start") return;  // the run's own start
                   const auto source = c.source.view();
                   const char* what =
                       c.name == "hold"
                           ? "the cell comes to rest and holds; type unhold to go on, or stop to end"
                       : c.name == "unhold" ? "checking the latched faults: Unholding follows, or a refusal"
                       : c.name == "stop"   ? "the cell comes to a controlled stop and the run ends"
                       : c.name == "abort"  ? "the cell stops at once and the run ends"
                                            : "done";
                   // An unhold is judged after it is journaled (a latched fault refuses it): received, not
                   // accepted. From the page or the plant: whose it was, so that the operator at the terminal
                   // knows.
                   const auto by = source == "terminal" || source.empty() ? std::string()
                                                                          : fmt::format(" (from {})", source);
                   screen_.message(fmt::format("{} {}{}: {} — {}", at(e.t), c.name, by,
                                               c.name == "unhold" ? "received" : "accepted", what));
                 },
                 [&](const journal::Fault& f) {
                   const int category = f.category;
                   screen_.message(
                       fmt::format("{} {}", at(e.t),
                                   screen_.paint("1;31", fmt::format("FAULT {} (stop category {}): {}",
                                                                     f.rule, category, f.detail.view()))));
                   if (f.rule == "operator_stop" && category == 2)
                     screen_.message(
                         "           Ctrl-C: the cell holds — type `stop` to end, or `reset` then `unhold` "
                         "to go on; "
                         "Ctrl-C again "
                         "is an emergency stop");
                   else if (category == 2)
                     screen_.message(
                         "           the cell holds — type `reset` then `unhold` to go on, or `stop` to end");
                   else
                     screen_.message(fmt::format("           the run stops (category {})", category));
                 },
                 [&](const journal::FaultCleared& f) {
                   screen_.message(fmt::format("{} fault cleared: {}", at(e.t), f.rule));
                 },
                 [&](const journal::StepEnded& s) {
                   if (s.ok) return;
                   screen_.message(
                       fmt::format("{} {}", at(e.t),
                                   screen_.paint("31", fmt::format("step {} failed: {} — {}", s.index + 1,
                                                                   s.label, s.detail.view()))));
                 },
                 [&](const journal::InjectedFault& f) {
                   screen_.message(fmt::format(
                       "{} {}", at(e.t), screen_.paint("35", "injected fault: " + journal::describe(f))));
                 },
                 [](const auto&) {},
             },
             e.payload);
}

void RunNarrator::on_note(double t, std::string_view text) {
  if (contains(text, "operator typed")) return;  // the console has answered it
  const std::string words(text);
  if (contains(text, "faults reset")) {
    screen_.message(fmt::format("{} reset: done, faults cleared — {}", at(t), next_step_hint()));
  } else if (contains(text, "reset refused")) {
    screen_.message(fmt::format("{} {} — remove the cause, then type reset again", at(t),
                                screen_.paint("33", "refused: " + words)));
  } else if (contains(text, "unhold refused")) {
    screen_.message(
        fmt::format("{} {} — type reset, then unhold", at(t), screen_.paint("33", "refused: " + words)));
  } else if (contains(text, "not possible")) {
    screen_.message(
        fmt::format("{} {} — {}", at(t), screen_.paint("33", "refused: " + words), next_step_hint()));
  } else {
    screen_.message(fmt::format("{} note: {}", at(t), text));
  }
}

}  // namespace cellctl::cli

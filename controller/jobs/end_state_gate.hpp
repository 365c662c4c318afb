#pragma once
// A job's end state is told only once its work is saved (issue 22, "an end state means the work is
// saved"): the run's events go on to the plant link and the page as they are recorded, except the
// state change into Complete, Stopped or Aborted, which waits until the job has written what it writes
// — the journal's summary (the run has ended), the home record, a taught config — and then goes on with
// what the job did appended to its reason. A plant that starts the next job on Complete so finds the
// home record and the taught resolution on disk.

#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "journal/event_listener.hpp"

namespace cellctl::jobs {

// The end state held back, a copy of its own: told after the run, whose names it no longer sees.
struct HeldEndState {
  double t = 0.0;
  std::string from;
  std::string to;
  journal::Text reason;
  [[nodiscard]] journal::Event event() const { return {t, journal::StateChanged{from, to, reason}}; }
};

class EndStateGate final : public journal::EventListener {
 public:
  // `next`: who hears the run's events through the gate (may be null: nobody).
  explicit EndStateGate(journal::EventListener* next) : next_(next) {}

  // The run's listener (on the journal's thread).
  void on_event(const journal::Event& e) override {
    if (const auto* s = std::get_if<journal::StateChanged>(&e.payload); s && is_end(s->to)) {
      const std::lock_guard lock(mutex_);
      held_ = HeldEndState{e.t, std::string(s->from), std::string(s->to), s->reason};
      return;
    }
    if (next_) next_->on_event(e);
  }
  void on_note(double t, std::string_view text) override {
    if (next_) next_->on_note(t, text);
  }

  // Once the job's work is on disk: the held end state goes on, `words` appended to its reason. A run
  // that never reached an end state (it could not start) has nothing held.
  void release(const std::string& words = {}) {
    const auto held = take(words);
    if (held && next_) next_->on_event(held->event());
  }
  // The held end state with `words` appended to its reason, for the caller to tell when it is ready
  // for what it will bring (serve: once it takes the next command); none when nothing is held.
  [[nodiscard]] std::optional<HeldEndState> take(const std::string& words = {}) {
    std::optional<HeldEndState> held;
    {
      const std::lock_guard lock(mutex_);
      held.swap(held_);
    }
    if (held && !words.empty()) held->reason = journal::Text::format("{}; {}", held->reason.view(), words);
    return held;
  }

 private:
  static bool is_end(std::string_view to) { return to == "Complete" || to == "Stopped" || to == "Aborted"; }

  journal::EventListener* next_;
  std::mutex mutex_;
  std::optional<HeldEndState> held_;
};

}  // namespace cellctl::jobs

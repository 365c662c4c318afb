#include "command/arbiter.hpp"

#include <fmt/format.h>

namespace cellctl::command {

Arbiter::Arbiter(std::chrono::milliseconds max_age, Tell tell, State initial)
    : max_age_(max_age), tell_(std::move(tell)), state_(initial) {}

State Arbiter::state_locked() const {
  if (!job_) return state_;
  return port_.state ? port_.state() : State::starting;  // a job begun but not reachable yet: starting
}

std::string Arbiter::stale(const Order& o) const {
  return expired(o, std::chrono::steady_clock::now(), std::chrono::system_clock::now(), max_age_);
}

Taken Arbiter::refuse(std::string why) {
  ++counters_.refused;
  return {Taken::How::refused, std::move(why)};
}

Taken Arbiter::command(Command c, const Order& o) {
  const std::lock_guard lock(mutex_);
  const auto word = supervisor::to_string(c);
  if (c == Command::start) return refuse("start names what to start: use the start request");
  if (auto why = stale(o); !why.empty()) {
    ++counters_.expired;
    return refuse(fmt::format("{} {}", word, why));
  }
  const State s = state_locked();
  if (const auto why = supervisor::refusal(s, c); !why.empty())
    return refuse(fmt::format("{} is not possible in state {}: {}", word, supervisor::to_string(s), why));
  if (!job_) return between_jobs(c, o);
  ++counters_.taken;
  auto taken = port_.request(c, o.source);
  if (taken.how == Taken::How::refused) {
    --counters_.taken;
    ++counters_.refused;
  }
  return taken;
}

std::string Arbiter::start_refusal(const Order& o) {
  const std::lock_guard lock(mutex_);
  if (auto why = stale(o); !why.empty()) return "start " + why;
  const State s = state_locked();
  if (const auto why = supervisor::refusal(s, Command::start); !why.empty())
    return fmt::format("start is not possible in state {}: {}", supervisor::to_string(s), why);
  return {};
}

Taken Arbiter::start(const Order& o, const std::function<Taken()>& begin) {
  const std::lock_guard lock(mutex_);
  if (auto why = stale(o); !why.empty()) {
    ++counters_.expired;
    return refuse("start " + why);
  }
  const State s = state_locked();
  if (const auto why = supervisor::refusal(s, Command::start); !why.empty())
    return refuse(fmt::format("start is not possible in state {}: {}", supervisor::to_string(s), why));
  auto taken = begin();
  if (taken.how == Taken::How::refused) {
    ++counters_.refused;
    return taken;
  }
  ++counters_.taken;
  job_ = true;
  return taken;
}

void Arbiter::attach(JobPort port) {
  const std::lock_guard lock(mutex_);
  port_ = std::move(port);
}

void Arbiter::job_ended(State final_state) {
  const std::lock_guard lock(mutex_);
  job_ = false;
  state_ = final_state;
}

void Arbiter::ignore(const std::string& words) {
  {
    const std::lock_guard lock(mutex_);
    ++counters_.ignored;
  }
  // Told outside the lock: journaling may wait for the loop to take earlier notes, and a flood of
  // ignored messages must never hold a stop back.
  if (tell_.note) tell_.note(words);
}

State Arbiter::state() {
  const std::lock_guard lock(mutex_);
  return state_locked();
}

ArbiterCounters Arbiter::counters() {
  const std::lock_guard lock(mutex_);
  return counters_;
}

void Arbiter::enter(State next, const std::string& reason) {
  if (tell_.state) tell_.state(state_, next, reason);
  state_ = next;
}

Taken Arbiter::between_jobs(Command c, const Order& o) {
  // No job: nothing moves, so each PackML transition is complete at once; the acting state is told
  // all the same, so that whoever follows the states sees PackML's sequence.
  ++counters_.taken;
  if (tell_.command) tell_.command(c, o.source);
  const auto by = fmt::format("{} by {}", supervisor::to_string(c), o.source.words());
  switch (c) {
    case Command::reset:
      enter(State::resetting, by);
      enter(State::idle, "reset done");
      return {Taken::How::done, "reset: the cell is Idle; a start is taken"};
    case Command::clear:
      enter(State::clearing, by);
      enter(State::stopped, "cleared: reset to reach Idle");
      return {Taken::How::done, "cleared: the cell is Stopped; reset to reach Idle"};
    case Command::stop:
      enter(State::stopping, by);
      enter(State::stopped, "no job was in progress: nothing moved");
      return {Taken::How::done, "stopped: no job was in progress; reset to reach Idle"};
    case Command::abort:
      enter(State::aborting, by);
      enter(State::aborted, "no job was in progress: nothing moved");
      return {Taken::How::done, "aborted: no job was in progress; clear, then reset to reach Idle"};
    case Command::start:
    case Command::hold:
    case Command::unhold:
      break;  // refused by the interlocks before: no job is in progress to hold
  }
  --counters_.taken;
  return refuse(fmt::format("{} needs a job in progress", supervisor::to_string(c)));
}

}  // namespace cellctl::command

#pragma once
// The one place that decides whether a command is taken now. The terminal, the web page and the plant
// all reach the cell through it; it judges every command by
//   1. its age (order.hpp): one that waited too long anywhere is answered "expired", not obeyed;
//   2. the present state, by PackML's interlocks (supervisor::refusal, the table the supervisor
//      judges its run by as well): Start only in Idle; Complete and Stopped reach Idle by Reset;
//      Aborted needs Clear, then Reset.
// A job in progress (a recipe's run, homing, a Teach-In; `cellctl run`'s one run) is reached through
// its JobPort: its own state, and its command path. Between jobs the arbiter holds the cell's state
// itself — the state the last job ended in, until the operator resets (or clears) it — and makes those
// transitions itself, telling them like a run's (Tell).
//
// Stops are never starved: the arbiter's lock is held only for a judgement and a hand-over (a
// run's request is an atomic bit; a start's begin registers the job, it does not run it), and a
// start's recipe is validated by the caller outside it, after start_refusal() said a start would be
// taken at all — so a flood of starts costs a comparison each. Thread-safe.

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>

#include "command/order.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::command {

using supervisor::Command;
using supervisor::State;

// How a command or a start was taken.
struct Taken {
  enum class How {
    by_run,   // handed to the run: its journaled outcome is the answer
    done,     // done at once: `text` is the outcome
    refused,  // refused at once: `text` is the reason
  };
  How how = How::refused;
  std::string text;
};

// The job in progress, as the arbiter reaches it.
struct JobPort {
  std::function<State()> state;                                 // the job's state now
  std::function<Taken(Command, const CommandSource&)> request;  // a command the interlocks allowed
};

// What the arbiter says of itself, on the caller's thread: `command` and `state` between jobs, under
// the arbiter's lock; `note` (an ignored message) at any time, outside it.
struct Tell {
  std::function<void(Command, const CommandSource&)> command;                  // a command it took
  std::function<void(State from, State to, const std::string& reason)> state;  // a state it entered
  std::function<void(const std::string&)> note;                                // one it ignored
};

struct ArbiterCounters {
  std::uint64_t taken = 0;
  std::uint64_t refused = 0;  // by the state, or expired
  std::uint64_t expired = 0;
  std::uint64_t ignored = 0;  // never judged: a retained message
};

class Arbiter {
 public:
  Arbiter(std::chrono::milliseconds max_age, Tell tell, State initial = State::idle);

  // A command other than a start.
  [[nodiscard]] Taken command(Command c, const Order& o);
  // Why a start would not be taken now (its age, the state), empty when it would: cheap, for the
  // caller to ask before it validates what the start names.
  [[nodiscard]] std::string start_refusal(const Order& o);
  // A start, judged again; when taken, `begin` registers the job (under the arbiter's lock, so no
  // second start can come between) and says what was started, or why it refused. A job begun is in
  // progress until job_ended().
  [[nodiscard]] Taken start(const Order& o, const std::function<Taken()>& begin);
  // The job is reached through `port` until it ends.
  void attach(JobPort port);
  // The job ended in `final_state` (Complete, Stopped or Aborted): the cell stays there until reset.
  void job_ended(State final_state);
  // A message that is never obeyed, whatever it says (a retained command): journaled and counted.
  void ignore(const std::string& words);

  [[nodiscard]] State state();
  [[nodiscard]] ArbiterCounters counters();
  [[nodiscard]] std::chrono::milliseconds max_age() const noexcept { return max_age_; }

 private:
  [[nodiscard]] State state_locked() const;
  [[nodiscard]] std::string stale(const Order& o) const;
  // Reset, clear, stop and abort between jobs: the arbiter's own transitions.
  [[nodiscard]] Taken between_jobs(Command c, const Order& o);
  void enter(State next, const std::string& reason);
  [[nodiscard]] Taken refuse(std::string why);

  const std::chrono::milliseconds max_age_;
  Tell tell_;
  std::mutex mutex_;
  State state_;       // between jobs
  bool job_ = false;  // a job is in progress: state and commands are its own
  JobPort port_;      // set by attach() while a job is in progress
  ArbiterCounters counters_;
};

}  // namespace cellctl::command

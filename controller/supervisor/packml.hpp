#pragma once
// The cell's states and commands, after PackML (ISA-TR88.00.02), reduced to what one cell needs, and
// the one table that says which command each state takes (refusal()). The supervisor judges a run's
// commands by it and the command arbiter (command/arbiter.hpp) every command from outside by it, so
// the terminal, the page and the plant meet the same interlocks.

#include <cstdint>
#include <string_view>

namespace cellctl::supervisor {

enum class State : std::uint8_t {
  idle,
  starting,  // waiting for every device session to be up and the encoder ready
  execute,   // running the recipe's steps
  holding,   // axes coming to a controlled stop, spindle kept (stop category 2)
  held,
  unholding,  // resuming the interrupted step
  stopping,   // axes and spindle coming to a controlled stop (category 1)
  stopped,
  aborting,  // SCU emergency stop and spindle stop at once (category 0)
  aborted,
  completing,  // recipe done, making sure everything is at rest
  complete,
  resetting,
  clearing,  // Aborted on its way to Stopped: the operator has acknowledged the abort
};

enum class Command : std::uint8_t { start, hold, unhold, stop, abort, reset, clear };

inline constexpr std::size_t kCommands = 7;

[[nodiscard]] constexpr std::string_view to_string(State s) noexcept {
  constexpr std::string_view names[] = {"Idle",       "Starting", "Execute",   "Holding",  "Held",
                                        "Unholding",  "Stopping", "Stopped",   "Aborting", "Aborted",
                                        "Completing", "Complete", "Resetting", "Clearing"};
  return names[static_cast<std::size_t>(s)];
}

[[nodiscard]] constexpr std::string_view to_string(Command c) noexcept {
  constexpr std::string_view names[] = {"start", "hold", "unhold", "stop", "abort", "reset", "clear"};
  return names[static_cast<std::size_t>(c)];
}

// The run is over in these states (until a reset, or a clear and a reset after Aborted).
[[nodiscard]] constexpr bool is_final(State s) noexcept {
  return s == State::complete || s == State::stopped || s == State::aborted;
}

// Why state `s` does not take command `c` (the words after "<command> is not possible in state <S>:"),
// or an empty view when it takes it. PackML's interlocks: Start only in Idle; Complete and Stopped
// reach Idle by Reset; Aborted needs Clear (to Stopped), then Reset. A reset in a running state only
// clears the monitor's latches (a category-2 stop's Held, say): it is taken, and changes no state.
[[nodiscard]] constexpr std::string_view refusal(State s, Command c) noexcept {
  const bool stopping_or_stopped = s == State::stopping || s == State::stopped || s == State::aborting ||
                                   s == State::aborted || s == State::clearing;
  switch (c) {
    case Command::start:
      if (s == State::idle) return {};
      if (s == State::complete || s == State::stopped) return "reset first: Start is taken only in Idle";
      if (s == State::aborted) return "clear, then reset: Start is taken only in Idle";
      return "a job is in progress: Start is taken only in Idle";
    case Command::hold:
      if (s == State::execute || s == State::unholding) return {};
      return "hold is taken only in Execute";
    case Command::unhold:
      // Also while still holding: a move goes on from the moving state the brake has reached.
      if (s == State::held || s == State::holding) return {};
      return "unhold is taken only in Held or Holding";
    case Command::stop:
      if (s == State::complete) return "the run is complete and the cell at rest: reset to Idle";
      if (!stopping_or_stopped && s != State::resetting) return {};
      return "the cell is stopping or stopped already";
    case Command::abort:
      if (s != State::aborting && s != State::aborted && s != State::clearing) return {};
      return "the cell is aborting or aborted already";
    case Command::reset:
      if (s == State::complete || s == State::stopped) return {};
      if (s == State::aborted) return "clear first: Aborted takes Clear, then Reset";
      if (s == State::idle || s == State::resetting || s == State::clearing || s == State::stopping ||
          s == State::aborting)
        return "nothing to reset";
      return {};  // a running state: the monitor's latches are judged, the state stays
    case Command::clear:
      if (s == State::aborted) return {};
      return "clear is taken only in Aborted";
  }
  return "unknown command";
}

}  // namespace cellctl::supervisor

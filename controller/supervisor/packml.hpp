#pragma once
// The supervisor's states and commands, after PackML (ISA-TR88.00.02), reduced to what one cell
// needs. Stopped and Aborted are left only by Reset, which the monitor allows only when every
// latched fault's cause is gone.

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
};

enum class Command : std::uint8_t { start, hold, unhold, stop, abort, reset };

[[nodiscard]] constexpr std::string_view to_string(State s) noexcept {
  constexpr std::string_view names[] = {"Idle",       "Starting", "Execute",  "Holding",  "Held",
                                        "Unholding",  "Stopping", "Stopped",  "Aborting", "Aborted",
                                        "Completing", "Complete", "Resetting"};
  return names[static_cast<std::size_t>(s)];
}

[[nodiscard]] constexpr std::string_view to_string(Command c) noexcept {
  constexpr std::string_view names[] = {"start", "hold", "unhold", "stop", "abort", "reset"};
  return names[static_cast<std::size_t>(c)];
}

// The run is over in these states (until a reset).
[[nodiscard]] constexpr bool is_final(State s) noexcept {
  return s == State::complete || s == State::stopped || s == State::aborted;
}

}  // namespace cellctl::supervisor

#pragma once
// What scu::Session made of a command (move_to, stop, set_speed, …): taken into its queue, or why
// not. A refusal is the session's own, decided before anything goes on the line; what the SCU answers
// later is in the snapshot (MoveOutcome::refused, last_refusal).

#include <cstdint>
#include <string_view>

namespace cellctl::scu {

enum class CommandStatus : std::uint8_t {
  taken,                 // queued (or already in force): on the line in this or a later cycle
  not_active,            // the session is not active: still opening remote mode, closing or faulted
  unknown_function,      // not a motion function (1..10) that the config defines
  bad_speed,             // the speed is not a number above 0
  emergency_stop_holds,  // an emergency stop (F20) is open: it is released first
  function_busy,         // the function's RE is still open, its RS on its way or a move of it queued
  wrong_actuators,       // a target for an actuator the function does not move, or one it moves left out
  target_out_of_range,   // a target is not a number or beyond the SCU's 32-bit position in edges
  queue_full,            // no room for the command's telegrams in the session's queue
  no_emergency_stop,     // a release with no emergency stop open
  unknown_data_id,       // a read of a data id whose value size the session does not know
};

[[nodiscard]] constexpr std::string_view to_string(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::taken:
      return "taken";
    case CommandStatus::not_active:
      return "the SCU session is not active";
    case CommandStatus::unknown_function:
      return "no such function in the config";
    case CommandStatus::bad_speed:
      return "the speed is not above 0";
    case CommandStatus::emergency_stop_holds:
      return "an emergency stop holds";
    case CommandStatus::function_busy:
      return "the function's last move is still open";
    case CommandStatus::wrong_actuators:
      return "the targets are not the function's actuators";
    case CommandStatus::target_out_of_range:
      return "a target is beyond the SCU's position range";
    case CommandStatus::queue_full:
      return "the session's telegram queue is full";
    case CommandStatus::no_emergency_stop:
      return "no emergency stop to release";
    case CommandStatus::unknown_data_id:
      return "a data id the session cannot read";
  }
  return "?";
}

struct [[nodiscard]] CommandResult {
  CommandStatus status = CommandStatus::taken;

  [[nodiscard]] constexpr bool taken() const noexcept { return status == CommandStatus::taken; }
  constexpr explicit operator bool() const noexcept { return taken(); }
  // A refusal that goes away by itself while the session works on (an RS or the queue draining,
  // remote mode opening, an emergency stop released after a reset): the same command may be taken in
  // a later cycle. The others refuse the same command for good.
  [[nodiscard]] constexpr bool worth_retrying() const noexcept {
    return status == CommandStatus::not_active || status == CommandStatus::function_busy ||
           status == CommandStatus::queue_full || status == CommandStatus::emergency_stop_holds;
  }
  constexpr bool operator==(const CommandResult&) const noexcept = default;
};

}  // namespace cellctl::scu

#pragma once
// What the SCU session publishes each receive(): per actuator its position in mm, decoded status 1,
// "initialised" from status 2 and its fault bit from the error word; per function the state of its
// RE/RS pair and the outcome of the last move; the typed error word, remote mode, the age of the
// positions, and the last RG result.

#include <array>
#include <bitset>
#include <cstdint>
#include <optional>

#include "link/clock.hpp"
#include "scu/protocol.hpp"
#include "scu/status_flags.hpp"

namespace cellctl::scu {

struct ActuatorState {
  bool configured = false;
  std::int32_t position_edges = 0;  // as the SCU reports it
  double position_mm = 0.0;         // position_edges ÷ the actuator's edges_per_mm
  Status1 status;                   // present, motion_active, in_position, out_position …
  bool initialised = false;         // actuator status 2 bit 0 (valid once Snapshot::status2_known)
  bool fault = false;               // the error word's bit for this actuator (15..20)
};

enum class MoveOutcome : std::uint8_t {
  none,           // no move asked
  queued,         // telegrams waiting to go out
  running,        // RE acknowledged, motion not yet ended
  arrived,        // motion ended within the tolerance of every target
  stopped_short,  // motion ended elsewhere: stopped, stalled (speed below threshold), fault
  refused,        // the SCU answered an error to one of the move's telegrams
};
[[nodiscard]] const char* to_string(MoveOutcome o) noexcept;

struct FunctionState {
  bool execution_open = false;  // RE acknowledged, its RS not yet
  MoveOutcome outcome = MoveOutcome::none;
  std::uint32_t executions = 0;     // REs the SCU acknowledged: one more, and the move asked is under way
  std::uint16_t speed_percent = 0;  // last remote speed written (the one place the speed is held)
  std::bitset<kActuatorCount> targeted;
  std::array<std::int32_t, kActuatorCount> targets{};  // edges, for the targeted actuators
};

struct LastRead {
  std::uint16_t data_id = 0;
  bool valid = false;
  Status status = Status::ack;
  wire::FixedBytes<kMaxReplyData> value;
  std::uint64_t sequence = 0;  // increments with every completed read
};

struct Refusal {
  Command command = Command::get;
  Status status = Status::ack;
};

struct Snapshot {
  std::array<ActuatorState, kActuatorCount> actuators{};        // [a-1]
  std::array<FunctionState, kMotionFunctionCount> functions{};  // [f-1]
  ErrorWord errors;
  bool remote_open = false;
  bool emergency_stop_open = false;  // F20 executed, its RS not yet sent
  bool watchdog_lapse_seen = false;  // error bit 22 was reported at least once
  std::uint64_t refreshes = 0;       // RC replies with position/status data
  std::optional<link::TimePoint> last_refresh;
  // Since the RC whose reply gave the positions was sent (or since activation without one), as of
  // receive(): the line's delay both ways is in it.
  link::Duration position_age{};
  bool status2_known = false;  // actuator status 2 read since activation: `initialised` is meaningful
  LastRead last_read;
  std::optional<Refusal> last_refusal;
  std::uint64_t refusals = 0;
};

}  // namespace cellctl::scu

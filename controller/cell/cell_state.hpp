#pragma once
// CellState: the one snapshot of the whole cell that the monitor and the supervisor read each cycle,
// in the program's units (mm, mm/s, Hz, s) with typed flags. Composed by runtime::CellDevices from the
// three sessions' snapshots, which did the decoding; plain data, so the monitor and supervisor can be
// tested on states made by hand.

#include <array>
#include <cstdint>
#include <string_view>

#include "link/clock.hpp"

namespace cellctl::cell {

inline constexpr std::size_t kMaxAxes = 6;

struct AxisState {
  bool present = false;       // the SCU reports the actuator
  double scu_mm = 0.0;        // the SCU's own position
  bool moving = false;        // SCU status 1: motion active (as of the last RC reply: it lags a command)
  bool commanded = false;     // a move is queued for the SCU or its RE is still open
  bool move_refused = false;  // the SCU answered an error to the last move's telegrams
  // The moves the SCU has taken for this axis (REs acknowledged): when it counts one more, the move
  // just asked for is under way, and its plan's clock may start.
  std::uint32_t moves_taken = 0;
  // SCU status 2 bit 0: the SCU has initialised the actuator (not the home record: routines/home_record).
  bool scu_initialised = false;
  bool at_retracted_end = false;  // SCU status 1: in position reached (the actuator's retracted end)
  bool at_extended_end = false;   // SCU status 1: out position reached
  bool actuator_fault = false;    // the SCU's error word names this actuator
  bool measured = false;          // the encoder measures this axis
  double encoder_mm = 0.0;        // valid when measured and the encoder is in data exchange
  double encoder_mm_s = 0.0;

  // The best position there is: the encoder's where it measures the axis, else the SCU's.
  [[nodiscard]] double position_mm() const noexcept { return measured ? encoder_mm : scu_mm; }
};

struct EncoderState {
  bool data_exchange = false;
  bool ready = false;         // status bit "Ready" (or data exchange in status-less modes)
  bool alarm = false;         // diagnosis: an alarm is set
  bool limit_switch = false;  // status bit "Limit switch"
  bool diagnosis_pending = false;
  double mm = 0.0;
  double mm_s = 0.0;
  // The last preset asked for by Intents::encoder (its id) and how it ended: the encoder acknowledged
  // it (done), or the handshake failed or the session refused to start it (failed, with the reason).
  std::uint32_t preset_id = 0;
  bool preset_done = false;
  bool preset_failed = false;
  std::string_view preset_failure = {};  // static text
};

struct SpindleState {
  bool active = false;  // session active
  double set_hz = 0.0;
  double actual_hz = 0.0;
  bool running = false;  // commanded to run
  bool at_speed = false;
  // At speed long enough that the frequency reading (polled slower than the status) is from after
  // the set speed was reached: only then is "off the set-point" meaningful.
  bool settled = false;
  bool at_rest = true;
  bool warning = false;
  bool fault = false;
  std::uint8_t fault_number = 0;
  bool over_temperature = false;
  bool current_limit = false;
  bool start_refused =
      false;  // the converter acknowledged a start but stayed at rest (error_number says why)
  std::uint8_t error_number = 0;  // the converter's warning or fault number
};

// The three devices of the cell, in their slots. A cell may have more (device_seam/device_registry.hpp
// registers them): up to kMaxDevices, in the slots after these.
enum class Device : std::uint8_t { scu, spindle, encoder };
inline constexpr std::size_t kDevices = 3;
inline constexpr std::size_t kMaxDevices = 8;
// A device's place in the arrays indexed by device (links, sessions).
[[nodiscard]] constexpr std::size_t slot(Device d) noexcept {
  return static_cast<std::size_t>(d);
}
[[nodiscard]] constexpr const char* to_string(Device d) noexcept {
  return d == Device::scu ? "scu" : d == Device::spindle ? "spindle" : "encoder";
}

// A link's exchanges since the session was built, for the plant's metrics (not for any rule).
struct LinkCounts {
  std::uint64_t good_replies = 0;
  std::uint64_t timeouts = 0;    // requests with no (complete) answer in time
  std::uint64_t bad_frames = 0;  // CRC/checksum/length errors and garbage
  std::uint64_t refusals = 0;    // well-formed replies in which the device refused
};

struct LinkState {
  bool active = false;          // the session is in its active state
  bool fault = false;           // the session gave up (its own link-fault deadline)
  link::Duration silent_for{};  // since the last good reply
  LinkCounts counts;
};

// The SCU's error word as the session typed it: the raw word for the record, the first cause named.
struct ScuErrors {
  std::uint32_t word = 0;        // error code 1, bits numbered from 1 = LSB
  int first_bit = 0;             // the lowest bit set, 0 with none
  std::string_view first_cause;  // the manual's cause for it (static text)
  [[nodiscard]] bool any() const noexcept { return word != 0; }
};

struct CellState {
  link::TimePoint now{};
  std::uint8_t axis_count = 0;
  std::array<AxisState, kMaxAxes> axes{};
  EncoderState encoder;
  SpindleState spindle;
  std::array<LinkState, kMaxDevices> links{};           // by slot; a slot without a device: active, no rule
  std::array<std::string_view, kMaxDevices> devices{};  // each slot's device by name, "" for none
  ScuErrors scu_errors;
  // Since the RC whose reply brought the SCU's positions was sent (every keep-alive): the line's
  // delay both ways is in it.
  link::Duration scu_position_age{};
  bool scu_remote = false;         // remote mode open (RO done, RC running)
  bool scu_status2_known = false;  // actuator status 2 (initialised) has been read since activation
  std::string_view scu_refusal;    // the SCU's last error reply, in words (static text)
};

}  // namespace cellctl::cell

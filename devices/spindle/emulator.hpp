#pragma once
// The e@syDrive converter as the program sees it over RS232: ACKs every SET and CMD, answers the three
// requests with live values, keeps silent on a bad checksum or an unknown message (the manual defines
// no negative acknowledge), drives a plant::SpindleMotor on its ramps, refuses to start unless P140 and
// P141 are "SycoDrive", latches faults with a five-entry history, counts operating hours. Fault hooks
// let tests break the line and the motor on purpose.

#include <array>
#include <cstdint>
#include <optional>

#include "link/clock.hpp"
#include "link/link.hpp"
#include "plant/spindle_motor.hpp"
#include "spindle/codec.hpp"
#include "wire/byte_queue.hpp"

namespace cellctl::spindle {

struct EmulatorConfig {
  double min_hz = 100.0;  // the motor's lowest and highest allowed set-point; outside → fault 51
  double max_hz = 1000.0;
  double ramp_up_hz_s = 400.0;
  double ramp_down_hz_s = 400.0;
  std::uint16_t converter_type = 4624;  // P36
  std::uint16_t firmware = 0x0433;      // P37: RS232 exists from firmware 4.3.3 on
  std::uint32_t serial_number = 1;      // P39
  double converter_hours = 0.0;         // P25 at start-up
  double motor_hours = 0.0;             // P26 at start-up
  std::uint8_t motor_code = 1;          // P20 / statusout4: M1
  double current_limit_a = 8.0;         // P11
  double dc_link_voltage_v = 48.0;      // P16
};

class Emulator {
 public:
  Emulator(link::Link& link, const EmulatorConfig& config);

  // Reads and answers requests, then steps the motor and the hour counters by the time since last poll.
  void poll(link::TimePoint now);

  [[nodiscard]] plant::SpindleMotor& motor() noexcept { return motor_; }
  [[nodiscard]] const EmulatorConfig& config() const noexcept { return config_; }

  // What the converter would report right now.
  [[nodiscard]] StatusOut statusout() const noexcept;
  [[nodiscard]] StatusValues status_values() const noexcept;
  [[nodiscard]] Identification identification() const noexcept;
  [[nodiscard]] const SetStart& start_parameters() const noexcept { return start_parameters_; }
  // The operating-hour counters (P25, P26) to the fraction, to carry them into the next emulator.
  [[nodiscard]] double converter_hours() const noexcept { return converter_seconds_ / 3600.0; }
  [[nodiscard]] double motor_hours() const noexcept { return motor_seconds_ / 3600.0; }
  // Well-formed frames it acted on, and frames it rejected (and so left unanswered).
  [[nodiscard]] std::uint64_t frames_handled() const noexcept { return frames_handled_; }
  [[nodiscard]] std::uint64_t frames_rejected() const noexcept { return frames_rejected_; }

  // --- fault injection ---
  // The motor's PTC: while hot, fault 31 is latched (the motor runs down) and reset cannot clear it.
  void set_over_temperature(bool hot) noexcept;
  // The current limit (WARNSTROM): warning 21 while active, the motor keeps running at the limit.
  void set_current_limit(bool active) noexcept { current_limit_ = active; }
  // Any fault number, latched like a real one until CMD System Reset.
  void inject_fault(std::uint8_t number) noexcept { latch_fault(number); }
  // The next n replies are not sent (the request itself is still carried out).
  void drop_next_replies(unsigned n) noexcept { drop_replies_ = n; }
  // The next reply goes out with a wrong checksum.
  void corrupt_next_checksum() noexcept { corrupt_next_ = true; }
  // A dead converter: reads and discards everything, answers nothing, until set_silent(false).
  void set_silent(bool silent) noexcept { silent_ = silent; }

 private:
  void handle(const Message& m);
  void handle_command(MsgId id);
  void handle_set_basic(const SetBasic& m);
  void reply(const Message& m);
  void latch_fault(std::uint8_t number) noexcept;
  void drive_motor() noexcept;
  [[nodiscard]] bool accelerating() const noexcept;
  void flush();

  link::Link& link_;
  EmulatorConfig config_;
  plant::SpindleMotor motor_;
  FrameDecoder decoder_;
  wire::ByteQueue<1024> tx_;

  SetStart start_parameters_{Source::digital_input, Source::digital_input, Direction::clockwise};  // factory
  std::uint16_t set_frequency_hz_ = 0;                                                             // P1
  bool running_ = false;        // started and neither stopped nor faulted
  bool start_refused_ = false;  // warning 140 showing
  bool over_temperature_ = false;
  bool current_limit_ = false;
  std::optional<std::uint8_t> fault_;  // latched fault number
  std::array<std::uint8_t, 5> fault_history_{};
  double converter_seconds_;
  double motor_seconds_;
  std::optional<link::TimePoint> last_poll_;

  unsigned drop_replies_ = 0;
  bool corrupt_next_ = false;
  bool silent_ = false;
  std::uint64_t frames_handled_ = 0;
  std::uint64_t frames_rejected_ = 0;
};

}  // namespace cellctl::spindle

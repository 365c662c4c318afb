#pragma once
// The master side of the e@syDrive link: a non-blocking state machine driven by the loop through
// link::DeviceSession (receive(now) … transmit(now)). One request in flight (the converter answers
// only when asked); commands go before polls and a stop before everything; every SET and CMD is
// confirmed by its ACK and repeated on silence a bounded number of times. It polls statusout fast (at
// speed, at rest, warnings) and the measured values slower, reads the identification once, and
// publishes all of it as a typed Snapshot in Hz with the age of each reading. Never sleeps, never
// blocks, does not allocate in receive() or transmit().

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "link/clock.hpp"
#include "link/device_session.hpp"
#include "link/link.hpp"
#include "link/link_health.hpp"
#include "spindle/codec.hpp"
#include "wire/byte_queue.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::spindle {

using namespace std::chrono_literals;

struct SessionConfig {
  link::Duration reply_timeout = 100ms;  // a 64-byte reply takes 17 ms at 38400 baud
  unsigned retries = 2;                  // further tries of a request after the first went unanswered
  link::Duration status_poll = 20ms;     // statusout (0x60): at speed, at rest, warning/fault
  link::Duration values_poll = 250ms;    // measured values (0x59)
  link::Duration link_fault_after = 1s;  // no good reply for this long → Lifecycle::fault
  // Send SET Startparameter (P140/P141 = SycoDrive, P146 = direction) before the first start. Off only
  // where the converter's sources are set on its panel and must not be touched from here.
  bool set_start_parameters = true;
};

struct Snapshot {
  // What this session asked for (the one place the commanded speed is held).
  bool run_requested = false;  // a start went out and no stop since
  double requested_frequency_hz = 0.0;
  Direction direction = Direction::clockwise;
  // From statusout (0x60).
  bool status_valid = false;    // at least one statusout since activation
  link::Duration status_age{};  // since the last statusout (or activation), as of receive()
  bool at_speed = false;        // N_Soll_OK
  bool at_rest = true;          // STILLSTAND
  DeviceState state = DeviceState::none;
  std::uint8_t error_number = 0;  // the warning's or fault's number, 0 with none
  bool current_limit = false;     // WARNSTROM
  bool motor_over_temperature = false;
  std::uint8_t motor_code = 0;
  // From the status values (0x59).
  bool values_valid = false;
  link::Duration values_age{};  // since the last status values (or activation), as of receive()
  // The frequency reading was asked for after N_Soll_OK came and it has held since: only then is
  // "actual off the set-point" meaningful (the values are polled slower than the status).
  bool settled = false;
  double set_frequency_hz = 0.0;      // P10, as the converter has it
  double actual_frequency_hz = 0.0;   // P13, unsigned
  double peak_current_a = 0.0;        // P11
  double motor_current_a = 0.0;       // P18
  double power_w = 0.0;               // P19
  double motor_voltage_v = 0.0;       // P15
  double dc_link_voltage_v = 0.0;     // P16
  std::uint32_t converter_hours = 0;  // P25
  std::uint32_t motor_hours = 0;      // P26
  // From the identification (0x5A), read once per activation.
  std::optional<Identification> identification;
  // Set when the converter acknowledged a start but stayed at rest with a warning or fault.
  bool start_refused = false;
  std::string start_refused_reason;

  [[nodiscard]] bool warning() const noexcept { return state == DeviceState::warning; }
  [[nodiscard]] bool fault() const noexcept { return state == DeviceState::fault; }
};

class Session final : public link::DeviceSession {
 public:
  Session(link::Link& link, const SessionConfig& config);

  void activate(link::TimePoint now) override;
  // Stops the spindle (CMD System Stopp, confirmed) and goes inactive once a statusout asked for after
  // the stop's ACK reports STILLSTAND; silent meanwhile for link_fault_after, it faults.
  void deactivate(link::TimePoint now) override;
  void receive(link::TimePoint now) override;
  void transmit(link::TimePoint now) override;
  [[nodiscard]] const link::LinkHealth& health() const noexcept override { return health_; }
  [[nodiscard]] bool awaiting_reply() const noexcept override { return in_flight_.has_value(); }

  // Commands; false when not active, out of range, or the command queue is full.
  [[nodiscard]] bool start(double frequency_hz, Direction direction = Direction::clockwise);
  [[nodiscard]] bool set_frequency(double frequency_hz);
  // Accepted whenever the session is active or deactivating; drops every queued command.
  [[nodiscard]] bool stop();
  [[nodiscard]] bool reset();
  // True while a SET or CMD is queued or waiting for its ACK.
  [[nodiscard]] bool commands_pending() const noexcept;

  [[nodiscard]] const Snapshot& snapshot() const noexcept { return snapshot_; }
  [[nodiscard]] const SessionConfig& config() const noexcept { return config_; }

 private:
  using Frame = wire::FixedBytes<kMaxFrameLength>;
  struct Outgoing {
    Frame frame;
    MsgId sent_id{};       // the MSGID of the request (for messages)
    MsgId answer_id{};     // the ACK's data for a SET/CMD, the RES MSGID for a request
    bool command = false;  // a SET or CMD: must be confirmed, else the session faults
  };
  static constexpr std::size_t kQueueCapacity = 8;

  [[nodiscard]] static Outgoing make(const Message& m);
  [[nodiscard]] bool enqueue(const Message& m);
  void read_replies(link::TimePoint now);
  void on_reply(link::TimePoint now, const Message& m);
  void on_statusout(const StatusOut& s);
  void on_values(const StatusValues& v);
  void check_in_flight(link::TimePoint now);
  void send_next(link::TimePoint now);
  void send(link::TimePoint now, const Outgoing& o);
  // Lifecycle::fault with the reason, queue dropped.
  template <class... Args>
  void fault(fmt::format_string<Args...> format, Args&&... args);

  link::Link& link_;
  SessionConfig config_;
  std::string link_name_;
  Snapshot snapshot_;
  link::LinkHealth health_;
  FrameDecoder decoder_;
  wire::ByteQueue<2 * kMaxFrameLength> tx_;

  std::array<Outgoing, kQueueCapacity> queue_{};  // commands, oldest first
  std::size_t queued_ = 0;
  std::optional<Outgoing> in_flight_;
  link::TimePoint sent_at_{};
  unsigned tries_ = 0;

  link::TimePoint activated_at_{};
  std::optional<link::TimePoint> status_at_;  // when the last statusout / values arrived
  std::optional<link::TimePoint> values_at_;
  std::optional<link::TimePoint> at_speed_since_;
  link::TimePoint next_status_at_{};
  link::TimePoint next_values_at_{};
  bool start_parameters_sent_ = false;
  Direction sent_direction_ = Direction::clockwise;
  bool watching_start_ = false;  // a start was acknowledged; the next statusout tells if it was taken
  std::optional<link::TimePoint> stop_acked_at_;  // the last CMD System Stopp's ACK
};

}  // namespace cellctl::spindle

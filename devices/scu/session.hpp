#pragma once
// The master side of one SCU: a non-blocking state machine over a Link, driven by the loop through
// link::DeviceSession (receive(now) … transmit(now)).
//
//   activate → RO(safety_id) → RC (no object: the manual wants RC before anything else)
//            → RT 0x3001 (CyclicObj 1 = CyclicLayout) → RC index 0 … active
//   active: RC index 0 every keepalive_period (watchdog 500 ms) refreshing every actuator at once;
//           RG 0x00E0 (actuator status 2: "initialised") after the first refresh and every 2 s;
//           queued RT/RE/RS/RG go out one at a time, stops first (and a stop preempts queued moves);
//           every RE is followed by its RS once the motion has ended (or on stop/shutdown).
//   deactivate → RS for every open RE → RA → inactive
//
// The session owns the SCU's units and bits: positions come and go in mm (edges ÷ edges_per_mm of
// each actuator, from the config), speeds in mm/s (% of the actuator's full speed), the status bytes
// and the error word are decoded here into the snapshot's typed flags.
//
// One request in flight; a reply time-out or a CSE is retried up to `retries` times; only an ACK counts
// as a sign of life (an SCU that answers nothing but errors goes silent and faults); a device silent
// for longer than link_fault_after is Lifecycle::fault with a reason. No allocation in receive() or
// transmit() (a fault reason is formatted into capacity reserved at construction).

#include <bitset>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "link/clock.hpp"
#include "link/device_session.hpp"
#include "link/link.hpp"
#include "link/link_health.hpp"
#include "scu/codec.hpp"
#include "scu/command_result.hpp"
#include "scu/cyclic_layout.hpp"
#include "scu/reply_stream.hpp"
#include "scu/session_config.hpp"
#include "scu/snapshot.hpp"
#include "scu/telegram_queue.hpp"

namespace cellctl::scu {

struct ActuatorTarget {
  int actuator = 1;  // 1..6
  double mm = 0.0;   // remote position
};

class Session final : public link::DeviceSession {
 public:
  // Throws std::invalid_argument for a bad config (see validate()).
  Session(link::Link& link, const SessionConfig& config);

  void activate(link::TimePoint now) override;
  void deactivate(link::TimePoint now) override;
  void receive(link::TimePoint now) override;
  void transmit(link::TimePoint now) override;
  [[nodiscard]] const link::LinkHealth& health() const noexcept override { return health_; }
  [[nodiscard]] bool awaiting_reply() const noexcept override { return in_flight_.has_value(); }

  // The commands: each is taken into the queue whole, or refused with its cause and nothing queued
  // (scu/command_result.hpp).
  //
  // Move function f (1..10) to remote positions: RT 0x3021.. per actuator, RT 0x3011.. speed, RE(f, 9).
  // Every actuator of the function needs a target. The speed is a percentage of the fastest of the
  // function's actuators (none goes faster than asked), at least 1 %. Refused while the function has
  // an RE open or a move queued, during an emergency stop, or when not active.
  CommandResult move_to(int function, std::span<const ActuatorTarget> targets, double speed_mm_s, bool soft);
  // RS for the function, ahead of everything queued; the function's queued move telegrams are dropped.
  CommandResult stop(int function, bool soft);
  // F20 ahead of everything (after a refused F20: behind the stops queued); every queued move is
  // dropped. Holds until release_emergency_stop(). Either, asked again while one is on its way, is
  // taken without a second telegram.
  CommandResult emergency_stop();
  CommandResult release_emergency_stop();
  // RT 0x3011.. while the function moves: the SCU changes speed keeping its ramp. Sends nothing when
  // the speed rounds to the percentage in force (taken: it is in force or on its way).
  CommandResult set_speed(int function, double speed_mm_s);
  // RG; the value lands in snapshot().last_read.
  CommandResult read(std::uint16_t data_id);

  [[nodiscard]] const Snapshot& snapshot() const noexcept { return snapshot_; }
  // When the last request went on the line (none yet: the epoch). Any of them may have reached the
  // SCU and restarted its communication time-out, so a bound on the SCU's own stop counts from here.
  [[nodiscard]] link::TimePoint last_sent() const noexcept { return sent_at_; }
  [[nodiscard]] const CyclicLayout& layout() const noexcept { return layout_; }
  [[nodiscard]] const SessionConfig& config() const noexcept { return config_; }

 private:
  enum class Purpose : std::uint8_t {
    open,
    first_keepalive,
    setup_cyclic,
    keepalive,
    position,
    speed,
    execute,
    stop,
    emergency_stop,
    release_emergency,
    read,
    status2,
    close
  };
  struct Pending {
    RequestBytes bytes;
    ReplyShape shape;
    Purpose purpose = Purpose::keepalive;
    std::uint8_t function = 0;  // fnc_ID (0-based) for moves and stops
    std::uint16_t data_id = 0;  // for reads
  };
  static constexpr std::size_t kQueueDepth = 24;

  [[nodiscard]] bool enqueue(bool urgent, const Request& r, Purpose p, std::uint8_t function = 0,
                             std::uint16_t data_id = 0);
  void read_link(link::TimePoint now);
  void on_reply(const Reply& reply, link::TimePoint now);
  void on_ack(const Reply& reply, const Pending& p, link::TimePoint now);
  void on_refusal(const Reply& reply, const Pending& p);
  void on_refresh(std::span<const std::uint8_t> data, link::TimePoint now);
  void on_status2(std::span<const std::uint8_t> data);
  void schedule_status2(link::TimePoint now);
  void retry_or_give_up(link::TimePoint now, const char* why);
  [[nodiscard]] bool defer_for_stop(link::TimePoint now);
  // A request of this purpose is queued as urgent or waits for its reply.
  [[nodiscard]] bool on_its_way(Purpose p) const noexcept;
  void send_next(link::TimePoint now);
  void send(const Pending& p, link::TimePoint now);
  void close_finished_executions();
  void drop_queued_moves(std::optional<std::uint8_t> function);
  // Lifecycle::fault with the reason; everything queued is dropped.
  template <class... Args>
  void fault(fmt::format_string<Args...> format, Args&&... args);
  [[nodiscard]] bool defined(int function) const noexcept;
  // The SCU's fnc_ID of a motion function: its 0-based number.
  [[nodiscard]] static std::uint8_t fnc(int function) noexcept {
    return static_cast<std::uint8_t>(function - 1);
  }
  [[nodiscard]] bool accepting() const noexcept { return lifecycle() == link::Lifecycle::active; }
  [[nodiscard]] std::uint16_t percent(int function, double speed_mm_s) const noexcept;

  link::Link& link_;
  std::string link_name_;  // link_.describe(), taken once at construction
  SessionConfig config_;
  CyclicLayout layout_;
  ReplyStream replies_;
  Snapshot snapshot_;
  link::LinkHealth health_;

  TelegramQueue<Pending, kQueueDepth> urgent_;  // stops
  TelegramQueue<Pending, kQueueDepth> normal_;  // everything else
  Pending keepalive_;
  std::optional<Pending> in_flight_;
  int attempts_ = 0;
  link::TimePoint sent_at_{};
  link::TimePoint activated_at_{};
  std::optional<link::TimePoint> positions_asked_at_;  // the last answered RC's sending
  bool last_sent_keepalive_ = false;                   // the telegram sent last was an RC
  bool keepalive_armed_ = false;
  link::TimePoint last_keepalive_sent_{};
  bool status2_queued_ = false;
  link::TimePoint next_status2_{};

  // Per function: RS already queued, and the refresh count at the RE's ACK (motion state from later
  // refreshes only counts).
  std::bitset<kMotionFunctionCount> stop_queued_;
  bool f20_refused_ = false;  // the last F20 answer was a refusal (a new one queues behind the stops)
  std::array<std::uint64_t, kMotionFunctionCount> execute_mark_{};
};

// (Here, for the session's sources: session.cpp, session_replies.cpp.)
template <class... Args>
void Session::fault(fmt::format_string<Args...> format, Args&&... args) {
  enter_fault(format, std::forward<Args>(args)...);
  urgent_.clear();
  normal_.clear();
  in_flight_.reset();
  replies_.expect_nothing();
  keepalive_armed_ = false;
}

}  // namespace cellctl::scu

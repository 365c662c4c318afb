#pragma once
// The master side of one SCU: a non-blocking state machine over a Link, stepped by poll(now).
//
//   activate → RO(safety_id) → RC (no object: the manual wants RC before anything else)
//            → RT 0x3001 (CyclicObj 1 = CyclicLayout) → RC index 0 … active
//   active: RC index 0 every keepalive_period (watchdog 500 ms) refreshing every actuator at once;
//           queued RT/RE/RS/RG go out one at a time, stops first (and a stop preempts queued moves);
//           every RE is followed by its RS once the motion has ended (or on stop/shutdown).
//   deactivate → RS for every open RE → RA → inactive
//
// One request in flight; a reply time-out or a CSE is retried up to `retries` times; a device silent
// for longer than link_fault_after is Lifecycle::fault with a reason. No allocation in poll() (a fault
// reason string is composed only when a fault happens).

#include <bitset>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "link/clock.hpp"
#include "link/fault_reason.hpp"
#include "link/lifecycle.hpp"
#include "link/link.hpp"
#include "link/link_health.hpp"
#include "scu/codec.hpp"
#include "scu/cyclic_layout.hpp"
#include "scu/reply_stream.hpp"
#include "scu/session_config.hpp"
#include "scu/snapshot.hpp"
#include "scu/telegram_queue.hpp"

namespace cellctl::scu {

struct ActuatorTarget {
  int actuator = 1;        // 1..6
  std::int32_t edges = 0;  // remote position
};

class Session {
 public:
  // Throws std::invalid_argument for a bad config (see validate()).
  Session(link::Link& link, const SessionConfig& config);

  void activate(link::TimePoint now);
  void deactivate(link::TimePoint now);
  [[nodiscard]] link::Lifecycle poll(link::TimePoint now);

  // Move function f (1..10) to remote positions: RT 0x3021.. per actuator, RT 0x3011.. speed, RE(f, 9).
  // Every actuator of the function needs a target. Refused while the function has an RE open or a
  // move queued, during an emergency stop, or when not active.
  [[nodiscard]] bool move_to(int function, std::span<const ActuatorTarget> targets,
                             std::uint16_t speed_percent, bool soft);
  // RS for the function, ahead of everything queued; the function's queued move telegrams are dropped.
  [[nodiscard]] bool stop(int function, bool soft);
  // F20 ahead of everything; every queued move is dropped. Holds until release_emergency_stop().
  [[nodiscard]] bool emergency_stop();
  [[nodiscard]] bool release_emergency_stop();
  // RT 0x3011.. while the function moves: the SCU changes speed keeping its ramp.
  [[nodiscard]] bool set_speed(int function, std::uint16_t speed_percent);
  // RG; the value lands in snapshot().last_read.
  [[nodiscard]] bool read(std::uint16_t data_id);

  [[nodiscard]] link::Lifecycle state() const noexcept { return state_; }
  [[nodiscard]] const Snapshot& snapshot() const noexcept { return snapshot_; }
  [[nodiscard]] const link::LinkHealth& health() const noexcept { return health_; }
  [[nodiscard]] const std::string& fault_reason() const noexcept { return fault_reason_; }
  [[nodiscard]] const CyclicLayout& layout() const noexcept { return layout_; }

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
  void receive(link::TimePoint now);
  void on_reply(const Reply& reply, link::TimePoint now);
  void on_ack(const Reply& reply, const Pending& p, link::TimePoint now);
  void on_refusal(const Reply& reply, const Pending& p);
  void on_refresh(std::span<const std::uint8_t> data, link::TimePoint now);
  void retry_or_give_up(link::TimePoint now, const char* why);
  [[nodiscard]] bool defer_for_stop(link::TimePoint now);
  void send_next(link::TimePoint now);
  void transmit(const Pending& p, link::TimePoint now);
  void close_finished_executions();
  void drop_queued_moves(std::optional<std::uint8_t> function);
  // Formats the reason into fault_reason_, whose capacity is reserved at construction: a fault found
  // in poll() allocates nothing.
  template <class... Args>
  void fault(fmt::format_string<Args...> format, Args&&... args);
  [[nodiscard]] bool defined(int function) const noexcept;
  [[nodiscard]] bool accepting() const noexcept { return state_ == link::Lifecycle::active; }

  link::Link& link_;
  std::string link_name_;  // link_.describe(), taken once at construction
  SessionConfig config_;
  CyclicLayout layout_;
  ReplyStream replies_;
  link::Lifecycle state_ = link::Lifecycle::inactive;
  std::string fault_reason_;
  Snapshot snapshot_;
  link::LinkHealth health_;

  TelegramQueue<Pending, kQueueDepth> urgent_;  // stops
  TelegramQueue<Pending, kQueueDepth> normal_;  // everything else
  Pending keepalive_;
  std::optional<Pending> in_flight_;
  int attempts_ = 0;
  link::TimePoint sent_at_{};
  link::TimePoint activated_at_{};
  bool keepalive_armed_ = false;
  link::TimePoint last_keepalive_sent_{};

  // Per function: RS already queued, and the refresh count at the RE's ACK (motion state from later
  // refreshes only counts).
  std::bitset<kMotionFunctionCount> stop_queued_;
  std::array<std::uint64_t, kMotionFunctionCount> execute_mark_{};
};

}  // namespace cellctl::scu

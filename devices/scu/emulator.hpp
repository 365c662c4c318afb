#pragma once
// An emulated Ewellix SCU on the device end of any Link: answers RO/RA/RC/RG/RT/RE/RS as the manual
// describes, from the same codec as the session, and drives one plant::Actuator per configured
// actuator. Remote-mode state machine: RO, then RC before any other command, then RC at least every
// 500 ms — else the watchdog stops motion per Safety_ID and sets error bit 22. Fault injection for
// tests: lost, late and damaged replies, actuator/over-current/synchronisation faults, and (through
// actuator(a).set_blocked) a jammed actuator.
//
// Reading of the manual where it is unclear (see the report in the commit): after a watchdog lapse
// with Safety_ID 0 only RC/RA/RO are accepted until the next RO; with Safety_ID 1/2 the next RC
// resumes remote mode. Bit 22 is cleared by RO; bits 14..21 by the next motion start. The manual names
// "initialization" (status 2 bit 0) but not how it is done: here an actuator is not initialised after
// power-up (unless EmulatorConfig::initialised says so) and becomes initialised when a run brings it
// into its retracted end (status 1 "in position"); a power cycle loses it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "link/clock.hpp"
#include "link/link.hpp"
#include "plant/actuator.hpp"
#include "scu/codec.hpp"
#include "scu/emulator_config.hpp"
#include "scu/request_stream.hpp"
#include "scu/status_flags.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::scu {

class Emulator {
 public:
  // Throws std::invalid_argument for an inconsistent config (see validate()).
  Emulator(link::Link& link, const EmulatorConfig& config);

  // Steps the actuators by the time since the last poll, runs the watchdog, answers what arrived.
  void poll(link::TimePoint now);

  // The plant of actuator a (1..6), e.g. to couple an encoder shaft to it or to jam it.
  // Throws std::out_of_range for an actuator the config does not have.
  [[nodiscard]] plant::Actuator& actuator(int a);
  [[nodiscard]] const plant::Actuator& actuator(int a) const;
  [[nodiscard]] std::int32_t position_edges(int a) const;
  [[nodiscard]] bool has_actuator(int a) const noexcept { return present(a); }
  [[nodiscard]] Status1 status1(int a) const;

  // Fault injection.
  void drop_next_replies(int n) noexcept { drop_replies_ = n; }
  void set_reply_delay(link::Duration d) noexcept { reply_delay_ = d; }
  void corrupt_next_reply_crc() noexcept { corrupt_next_ = true; }
  // The next n requests (of command `only`, when given) are answered with error status s and not
  // carried out: a refused move, a refused keep-alive, an SCU that answers nothing but errors.
  void refuse_next_requests(int n, Status s, std::optional<Command> only = std::nullopt) noexcept {
    refuse_count_ = n;
    refuse_status_ = s;
    refuse_only_ = only;
  }
  void inject_actuator_fault(int a);  // bit 15+a-1, actuator a fast-stopped
  // A lasting defect of actuator a (a broken sensor, a short): its fault is injected now and again at
  // every motion start while `on` — the bit is "reset with next motion" and set again at once, so the
  // actuator does not move. Throws std::out_of_range for an actuator the config does not have.
  void set_actuator_fault(int a, bool on);
  // Power lost and back: motion stops, remote mode is closed, and every actuator is no longer
  // initialised (status 2 bit 0) until it is driven into its retracted end again.
  void power_cycle();
  [[nodiscard]] bool initialised(int a) const noexcept { return present(a) && initialised_[index(a)]; }
  void inject_over_current();                     // bit 14, every actuator fast-stopped
  void inject_position_difference(int function);  // bit 21, the function's actuators fast-stopped

  // What a test checks.
  [[nodiscard]] bool remote_open() const noexcept { return remote_open_; }
  [[nodiscard]] bool watchdog_lapsed() const noexcept { return lapsed_; }
  [[nodiscard]] ErrorWord error_word() const noexcept { return ErrorWord(error_codes_[0]); }
  [[nodiscard]] bool execution_open(int function) const noexcept { return running_[index(function)]; }
  [[nodiscard]] bool emergency_stop_active() const noexcept { return emergency_stop_; }
  [[nodiscard]] std::uint64_t cyclic_count() const noexcept { return rc_count_; }
  // The longest time between two RC while remote mode was open: the watchdog margin actually seen.
  [[nodiscard]] link::Duration max_cyclic_gap() const noexcept { return max_rc_gap_; }
  [[nodiscard]] std::uint64_t requests_answered() const noexcept { return answered_; }
  [[nodiscard]] std::uint64_t discarded_partial_requests() const noexcept { return discarded_partials_; }

 private:
  // Its sources, one concept each: emulator.cpp (construction, a poll's order, the actuators as a test
  // reads them), emulator_telegrams.cpp (requests in, replies out, the reply faults),
  // emulator_remote_mode.cpp (RO/RC/RA and the watchdog), emulator_motion.cpp (RE/RS, the functions'
  // targets and speeds, the plant stepped), emulator_data_list.cpp (RG/RT: the readable and writable
  // data), emulator_faults.cpp (the error word, injected faults, a power cycle).

  static std::size_t index(int one_based) noexcept { return static_cast<std::size_t>(one_based - 1); }
  // index(a) of an actuator the config has; throws std::out_of_range for any other a.
  [[nodiscard]] std::size_t present_index(int a) const;
  // User positions structure (0x2001..): for each of 4 users Memory 1..4, Intermediate In/Out, then the
  // virtual limits. The emulator's defaults are fractions of the stroke, the same for every user: the
  // remote position's default, the targets of RE Memory/Intermediate, and what RG reads.
  static constexpr std::array<double, 6> kUserPositionFractions = {0.2, 0.4, 0.6, 0.8, 0.1, 0.9};
  struct Outgoing {
    ReplyBytes bytes;
    link::TimePoint due;
  };

  void step_plant(link::Duration dt);
  void run_watchdog(link::TimePoint now);
  void receive(link::TimePoint now);
  void answer(const Request& r, link::TimePoint now);
  void answer_error(std::uint8_t command_byte, Status s, link::TimePoint now);
  void send(const Reply& reply, link::TimePoint now);
  void flush(link::TimePoint now);

  Status handle(const OpenRequest& r, link::TimePoint now);
  Status handle(const AbortRequest& r, link::TimePoint now);
  Status handle(const CyclicRequest& r, link::TimePoint now, wire::ByteWriter& out);
  Status handle(const GetRequest& r, wire::ByteWriter& out);
  Status handle(const TransferRequest& r);
  Status handle(const ExecuteRequest& r);
  Status handle(const StopRequest& r);
  [[nodiscard]] Status remote_permission() const noexcept;

  [[nodiscard]] bool read_value(std::uint16_t id, wire::ByteWriter& out) const;
  void read_element(std::uint16_t id, wire::ByteWriter& out) const;
  [[nodiscard]] Status check_write(std::uint16_t id, std::span<const std::uint8_t> value) const;
  void apply_write(std::uint16_t id, std::span<const std::uint8_t> value);

  void start_function(std::size_t f, Direction d, bool soft);
  void stop_function(std::size_t f, bool soft);
  void stop_all(bool soft);
  [[nodiscard]] double target_mm(std::size_t a, Direction d) const;
  void raise_error(int bit);
  [[nodiscard]] bool present(int a) const noexcept {
    return a >= 1 && a <= kActuatorCount && config_.actuators[index(a)].present;
  }

  link::Link& link_;
  EmulatorConfig config_;
  std::vector<plant::Actuator> actuators_;  // always six; absent ones are never moved or reported
  RequestStream requests_;
  std::optional<link::TimePoint> last_poll_;

  // Remote mode.
  bool remote_open_ = false;
  bool rc_seen_ = false;
  bool lapsed_ = false;
  std::uint8_t safety_id_ = 0;
  link::TimePoint last_rc_at_{};
  std::uint64_t rc_count_ = 0;
  link::Duration max_rc_gap_{};

  // Remote data (0x3xxx) and the function state.
  std::array<std::array<std::uint16_t, 12>, kCyclicObjectCount> cyclic_objects_{};
  std::array<std::uint16_t, kMotionFunctionCount> remote_speed_{};
  std::array<std::int32_t, kActuatorCount> remote_position_{};
  std::array<bool, kMotionFunctionCount> running_{};  // RE given, RS not yet
  std::array<int, kActuatorCount> owner_{};           // function index driving the actuator, -1 none
  bool emergency_stop_ = false;
  std::uint8_t outputs_ = 0, buzzer_ = 0, hand_switch_leds_ = 0;

  // Readable data list state.
  std::array<std::uint32_t, 5> error_codes_{};  // 0x00D1 (latest) … 0x00D5
  std::array<std::uint32_t, kActuatorCount> relay_in_{}, relay_out_{}, actuator_errors_{};
  std::array<double, kActuatorCount> stroke_edges_{};
  std::array<bool, kActuatorCount> initialised_{};  // status 2 bit 0
  std::array<std::uint16_t, kActuatorCount> max_current_{};
  std::uint32_t over_current_count_ = 0;

  // Fault injection and the outgoing side.
  int drop_replies_ = 0;
  link::Duration reply_delay_{};
  bool corrupt_next_ = false;
  int refuse_count_ = 0;
  Status refuse_status_ = Status::permission_error;
  std::optional<Command> refuse_only_;
  std::array<bool, kActuatorCount> lasting_fault_{};
  static constexpr std::size_t kOutgoing = 4;
  std::array<Outgoing, kOutgoing> outgoing_{};
  std::size_t outgoing_count_ = 0;
  std::array<std::uint8_t, 2 * kMaxReplyTelegram> tx_{};
  std::size_t tx_size_ = 0;
  std::array<std::uint8_t, kMaxReplyData> reply_data_{};
  std::uint64_t answered_ = 0;
  std::uint64_t discarded_partials_ = 0;
};

}  // namespace cellctl::scu

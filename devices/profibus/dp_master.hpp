#pragma once
// A DP-V0 class 1 master for one slave, as a non-blocking state machine stepped by poll(now):
//
//   FDL_Status → Slave_Diag → Set_Prm → Chk_Cfg → Slave_Diag (ready, no Prm/Cfg fault)
//   → Data_Exchange every data_exchange_period
//
// with FCB/FCV kept per station (a request that got no reply is repeated with the SAME FCB, up to
// max_retries times, each after the slot time), DH in a Data_Exchange reply → Slave_Diag, a slave
// silent for lost_slave_time → start-up again. The master is the only sender on the line besides the
// slave it asks: it waits TSYN bit times of idle line before every request.
//
// Lifecycle: activating during start-up (and while a lost slave is looked for again), active in data
// exchange, fault when the start-up is refused — activate() again to retry — deactivating while
// Global_Control Clear_Data is sent on deactivate(). No allocation in poll().
//
// Who refused, and why, is part of the fault: the SLAVE refuses parameters (Prm_Fault, or RS to
// Set_Prm), configuration (Cfg_Fault) or a requested function (Not_Supported); OUR master refuses a
// slave whose ident number is not the configured one, or one that another master holds (its
// diagnosis names another master: Master_Lock, which the standard has the master set). The fault
// reason says which, with the slave's standard diagnosis in words.
//
// Replies that do not fit are never taken as data: a Slave_Diag reply shorter than its 6 standard
// octets, or a Data_Exchange reply whose length is not the configured input length, is counted
// (health().error_replies, stats().bad_inputs) and the start-up is begun again with the reason —
// the inputs are not refreshed and the link is not "active" meanwhile.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "link/clock.hpp"
#include "link/lifecycle.hpp"
#include "link/line_format.hpp"
#include "link/link.hpp"
#include "link/link_health.hpp"
#include "profibus/dp_diag.hpp"
#include "profibus/dp_services.hpp"
#include "profibus/fdl_codes.hpp"
#include "profibus/fdl_decoder.hpp"
#include "profibus/fdl_frame.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::profibus {

inline constexpr std::size_t kMaxUserPrm = kMaxData - kPrmStandardSize;
inline constexpr std::size_t kMaxIo = kMaxData;

struct DpMasterConfig {
  std::uint8_t master_address = 1;                    // 0..125
  link::LineFormat line = link::line_8e1(1'500'000);  // character and bit times
  std::uint32_t slot_time_bits = 300;                 // TSL: longest wait for the first octet of a reply
  std::uint8_t max_retries = 1;                       // repetitions of a request that got no reply
  std::uint8_t wd_fact_1 = 10;  // slave response watchdog = 10 ms × f1 × f2 (0: watchdog off)
  std::uint8_t wd_fact_2 = 10;
  std::uint8_t min_tsdr_bits = 11;                                     // sent to the slave in Set_Prm
  link::Duration data_exchange_period = std::chrono::milliseconds(1);  // 0: back to back
  link::Duration lost_slave_time = std::chrono::milliseconds(100);     // no good reply → start-up again
  link::Duration restart_delay = std::chrono::milliseconds(10);        // between start-up attempts
  std::uint8_t group = 0;                                              // Set_Prm group ident
};

struct DpSlaveSetup {
  std::uint8_t station_address = 1;  // 1..126 (126: only set_slave_address() is possible)
  std::uint16_t ident = 0;
  wire::FixedBytes<kMaxUserPrm> user_prm;  // Set_Prm octet 8 onwards
  wire::FixedBytes<kMaxData> cfg;          // Chk_Cfg identifier bytes
  std::size_t input_length = 0;            // Data_Exchange reply octets expected
  std::size_t output_length = 0;           // Data_Exchange request octets sent
  bool freeze_req = false;
  bool sync_req = false;
};

enum class DpState : std::uint8_t {
  stopped,       // not activated
  wait_address,  // station 126: nothing to do until set_slave_address()
  fdl_status,    // is anybody there?
  diag_initial,  // Slave_Diag before parameterisation
  set_prm,
  chk_cfg,
  diag_check,  // Slave_Diag after Chk_Cfg: must be ready
  data_exchange,
  diag_cyclic,   // Slave_Diag in data exchange (after DH)
  refused,       // Prm/Cfg fault: stays until activate()
  restart_wait,  // pause before the next start-up attempt
  clearing,      // deactivate(): Global_Control Clear_Data
};
[[nodiscard]] std::string_view to_string(DpState s) noexcept;

// Why the slave refused to enter data exchange, with the diagnosis that said so.
struct StartupFault {
  enum class Kind : std::uint8_t {
    none,
    prm_fault,       // the slave refused the parameters (diagnosis: Prm_Fault)
    cfg_fault,       // the slave refused the configuration (diagnosis: Cfg_Fault)
    not_supported,   // the slave does not support a requested function (Freeze/Sync)
    rejected,        // the slave answered Set_Prm with RS (service not activated for us)
    ident_mismatch,  // our master refused: the slave's ident number is not the configured one
    master_lock,     // our master refused: another master holds the slave
  };
  Kind kind = Kind::none;
  // True when the slave said no; false when it was our master that refused.
  [[nodiscard]] bool by_slave() const noexcept {
    return kind != Kind::ident_mismatch && kind != Kind::master_lock;
  }
  DpDiagnosis diagnosis;  // the Slave_Diag reply that showed it (the profile decodes the extended part)
};
[[nodiscard]] std::string_view to_string(StartupFault::Kind k) noexcept;

enum class RequestStatus : std::uint8_t { idle, pending, done, failed };

struct DpMasterStats {
  std::uint64_t data_exchanges = 0;  // good Data_Exchange replies
  std::uint64_t diag_reads = 0;
  std::uint64_t startups = 0;    // start-ups begun (the first and every restart)
  std::uint64_t lost = 0;        // times the slave was declared lost
  std::uint64_t bad_inputs = 0;  // Data_Exchange replies refused: wrong length, or reject_input()
  link::Duration last_cycle{};   // between the last two good Data_Exchange replies
  link::Duration max_cycle{};
  std::optional<link::TimePoint> last_input_at;  // when the last good input arrived
};

class DpMaster {
 public:
  // Throws std::invalid_argument naming the field and value (addresses, lengths, zero baud).
  DpMaster(link::Link& link, const DpMasterConfig& config, const DpSlaveSetup& setup);

  void activate(link::TimePoint now);
  // The slave's parameters and configuration for the next activate() (a re-parameterisation: Set_Prm
  // and Chk_Cfg go out again then). Ignored unless stopped (inactive or fault).
  void set_slave_setup(const DpSlaveSetup& setup) noexcept;
  // Orderly stop: Global_Control Clear_Data to the slave, then stopped (Lifecycle::inactive).
  void deactivate(link::TimePoint now);
  [[nodiscard]] link::Lifecycle poll(link::TimePoint now);
  // When poll() next has something to do without new octets (send, time out); nullopt: idle.
  [[nodiscard]] std::optional<link::TimePoint> next_deadline() const noexcept;

  [[nodiscard]] link::Lifecycle lifecycle() const noexcept { return lifecycle_; }
  [[nodiscard]] DpState dp_state() const noexcept { return state_; }
  [[nodiscard]] const std::string& fault_reason() const noexcept { return fault_reason_; }
  // Why the start-up was last begun again (slave lost, left data exchange, …); empty before.
  [[nodiscard]] const std::string& restart_reason() const noexcept { return restart_reason_; }
  [[nodiscard]] const link::LinkHealth& health() const noexcept { return health_; }
  [[nodiscard]] const DpMasterStats& stats() const noexcept { return stats_; }
  // Time since the last good input (since activation when there was none).
  [[nodiscard]] link::Duration input_age(link::TimePoint now) const noexcept;

  // Outputs sent with every Data_Exchange; false unless exactly output_length octets.
  [[nodiscard]] bool set_outputs(std::span<const std::uint8_t> outputs) noexcept;
  // The inputs of the last good Data_Exchange (input_length octets, zeros before the first).
  [[nodiscard]] std::span<const std::uint8_t> inputs() const noexcept { return inputs_.view(); }
  // The profile found the last inputs invalid (e.g. a bit the manual says is always 0): counted as
  // a bad exchange, and input_age() runs on from the last input that was good.
  void reject_input() noexcept;
  // The last Slave_Diag reply read.
  [[nodiscard]] const DpDiagnosis& diagnosis() const noexcept { return diagnosis_; }
  [[nodiscard]] const StartupFault& last_startup_fault() const noexcept { return startup_fault_; }
  [[nodiscard]] std::uint8_t station_address() const noexcept { return setup_.station_address; }

  // Global_Control to the configured group (or all slaves when the group is 0), sent as a broadcast
  // between two cycles. False when not activated or one is already waiting.
  [[nodiscard]] bool global_control(std::uint8_t commands) noexcept;
  [[nodiscard]] bool global_control(GlobalCommand command) noexcept {
    return global_control(static_cast<std::uint8_t>(command));
  }

  // Set_Slave_Add to the slave at the configured station address (normally 126). On the slave's
  // acknowledgement the master follows it to new_address and starts it up there. False when not
  // activated, the address is not 1..125, or a change is already pending.
  [[nodiscard]] bool set_slave_address(std::uint8_t new_address, bool no_add_chg) noexcept;
  [[nodiscard]] RequestStatus address_change_status() const noexcept { return address_change_; }

 private:
  // Its sources, as SOEM keeps configuration apart from the cyclic work: dp_master.cpp (the lifecycle,
  // the line: one poll, replies, time-outs and retries, FCB, state changes, Set_Slave_Add),
  // dp_master_startup.cpp (FDL_Status, Set_Prm, Chk_Cfg, the diagnosis and who refused),
  // dp_master_data_exchange.cpp (outputs, inputs and their age, DH, Global_Control).
  enum class Pending : std::uint8_t { none, cyclic, global_control, set_address };

  void send(const FdlFrame& frame, bool expect_reply, Pending pending, link::TimePoint now);
  void transmit(link::TimePoint now);
  void next_request(link::TimePoint now);
  void send_startup_request(link::TimePoint now);
  void send_data_exchange(link::TimePoint now);
  void send_global_control(link::TimePoint now);
  void send_clear_data(link::TimePoint now);
  void on_reply(const FdlFrame& reply, link::TimePoint now);
  void on_startup_reply(const FdlFrame& reply, link::TimePoint now);
  void on_no_reply(link::TimePoint now);
  void on_diag(const FdlFrame& reply, link::TimePoint now);
  void on_data(const FdlFrame& reply, link::TimePoint now);
  void enter(DpState s, link::TimePoint now);
  void restart(link::TimePoint now, std::string_view why);
  void refuse(StartupFault::Kind kind);
  // A reply whose length is outside [fewest, most] octets is not taken; start-up begins again.
  void restart_with_bad_reply(link::TimePoint now, std::string_view service, std::size_t octets,
                              std::size_t fewest, std::size_t most);
  [[nodiscard]] bool has_request(link::TimePoint now) const noexcept;
  [[nodiscard]] std::uint8_t next_fc(std::uint8_t function) noexcept;
  [[nodiscard]] FdlFrame sap_request(std::uint8_t dsap, std::span<const std::uint8_t> data) noexcept;

  link::Link& link_;
  DpMasterConfig config_;
  DpSlaveSetup setup_;
  link::Duration char_time_;
  link::Duration tsyn_;
  link::Duration slot_time_;

  link::Lifecycle lifecycle_ = link::Lifecycle::inactive;
  DpState state_ = DpState::stopped;
  link::TimePoint activated_at_{};
  link::TimePoint state_since_{};
  link::TimePoint next_cycle_at_{};

  // The request in flight.
  bool in_flight_ = false;
  bool expect_reply_ = false;
  Pending pending_ = Pending::none;
  wire::FixedBytes<kMaxFrameSize> request_bytes_;  // kept for a repetition with the same FCB
  std::uint8_t attempts_ = 0;
  link::TimePoint sent_at_{};
  link::TimePoint reply_deadline_{};
  bool reply_started_ = false;
  link::TimePoint line_idle_from_{};  // last octet seen or sent on the line; next request after + TSYN
  FdlDecoder decoder_;

  // FCB per station: the next FCB to use and whether FCV may be set (after the first request).
  struct FcbState {
    bool started = false;
    bool fcb = true;
  };
  std::array<FcbState, 128> fcb_{};

  wire::FixedBytes<kMaxIo> outputs_;
  wire::FixedBytes<kMaxIo> inputs_;
  DpDiagnosis diagnosis_;
  StartupFault startup_fault_;

  std::optional<GlobalControl> global_control_;
  std::optional<SetSlaveAdd> address_request_;
  RequestStatus address_change_ = RequestStatus::idle;

  link::LinkHealth health_;
  DpMasterStats stats_;
  std::optional<link::TimePoint> previous_input_at_;  // restored by reject_input()
  std::string fault_reason_;
  std::string restart_reason_;
};

}  // namespace cellctl::profibus

#pragma once
// The generic DP-V0 slave (emulator side) over any Link: answers FDL_Status, Slave_Diag, Set_Prm,
// Chk_Cfg, Get_Cfg, Rd_Inp, Rd_Outp, Set_Slave_Add, Global_Control and Data_Exchange at its station
// address with the standard state machine Wait_Prm → Wait_Cfg → Data_Exchange, the standard
// diagnosis bits, FCB/FCV repetition handling and the response watchdog. The device behaviour is
// the SlaveBehaviour it is given.
//
// Timing: a reply is written no earlier than min_TSDR bit times after the request's last octet
// arrived (next_deadline() says when, so a virtual-time driver can step to it).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "link/clock.hpp"
#include "link/line_format.hpp"
#include "link/link.hpp"
#include "profibus/dp_diag.hpp"
#include "profibus/fdl_codes.hpp"
#include "profibus/fdl_decoder.hpp"
#include "profibus/fdl_frame.hpp"
#include "profibus/slave_behaviour.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::profibus {

struct DpSlaveConfig {
  std::uint8_t address = kDefaultSlaveAddress;  // 1..126; 126 serves only Set_Slave_Add (and status)
  std::uint16_t ident = 0;
  link::LineFormat line = link::line_8e1(1'500'000);  // bit times for min_TSDR
  // False models rotary switches set to a real address: Set_Slave_Add is refused.
  bool address_change_allowed = true;
  bool freeze_supported = true;
  bool sync_supported = true;
};

enum class DpSlaveState : std::uint8_t { wait_prm, wait_cfg, data_exchange };
[[nodiscard]] std::string_view to_string(DpSlaveState s) noexcept;

class DpSlave {
 public:
  // Throws std::invalid_argument for an address outside 1..126.
  DpSlave(link::Link& link, const DpSlaveConfig& config, SlaveBehaviour& behaviour);

  // Reads requests, answers those addressed to this station, runs the watchdog.
  void poll(link::TimePoint now);
  // When poll() has something to do without new octets (a reply due, the watchdog); nullopt: nothing.
  [[nodiscard]] std::optional<link::TimePoint> next_deadline() const noexcept;

  [[nodiscard]] std::uint8_t address() const noexcept { return address_; }
  [[nodiscard]] DpSlaveState state() const noexcept { return state_; }
  // The standard diagnosis as it would be sent now.
  [[nodiscard]] StandardDiag standard_diag() const;
  // The behaviour's reason for the last refused Set_Prm (empty when the last one was accepted).
  [[nodiscard]] std::string_view last_prm_reason() const noexcept { return prm_reason_; }
  // The outputs of the last Data_Exchange (after Clear_Data: zeros).
  [[nodiscard]] std::span<const std::uint8_t> outputs() const noexcept { return outputs_.view(); }

  struct Counters {
    std::uint64_t requests = 0;        // requests addressed to this station
    std::uint64_t repeats = 0;         // answered with the previous reply (same FCB)
    std::uint64_t data_exchanges = 0;  // executed Data_Exchange requests
    std::uint64_t bad_frames = 0;
    std::uint64_t watchdog_expiries = 0;
    std::uint64_t locked_refusals = 0;  // Set_Prm from another master while locked (answered RS)
  };
  [[nodiscard]] const Counters& counters() const noexcept { return counters_; }

  // Fault injection: a silent slave reads and discards everything and answers nothing.
  void set_silent(bool silent) noexcept { silent_ = silent; }

 private:
  void handle(const FdlFrame& request, link::TimePoint now);
  [[nodiscard]] FdlFrame execute(const FdlFrame& request, link::TimePoint now);
  [[nodiscard]] FdlFrame serve_sap(const FdlFrame& request, link::TimePoint now);
  [[nodiscard]] bool set_prm(std::span<const std::uint8_t> data, std::uint8_t master, link::TimePoint now);
  [[nodiscard]] bool chk_cfg(std::span<const std::uint8_t> data);
  [[nodiscard]] FdlFrame data_exchange(const FdlFrame& request);
  void global_control(const FdlFrame& request);
  [[nodiscard]] bool set_slave_add(std::span<const std::uint8_t> data);
  [[nodiscard]] FdlFrame diag_reply(const FdlFrame& request);
  void leave_data_exchange(LeaveReason reason);
  void check_watchdog(link::TimePoint now);
  void send_due(link::TimePoint now);

  link::Link& link_;
  DpSlaveConfig config_;
  SlaveBehaviour& behaviour_;
  std::uint8_t address_;
  bool address_locked_ = false;  // No_Add_Chg received
  DpSlaveState state_ = DpSlaveState::wait_prm;
  FdlDecoder decoder_;
  link::Duration min_tsdr_;

  // Set by the accepted Set_Prm.
  std::uint8_t master_ = kNoMaster;
  bool prm_fault_ = false;
  bool cfg_fault_ = false;
  bool not_supported_ = false;
  bool wd_on_ = false;
  link::Duration watchdog_{};
  std::optional<link::TimePoint> watchdog_deadline_;
  std::uint8_t group_ = 0;
  std::string_view prm_reason_;
  wire::FixedBytes<kMaxData> cfg_;

  // Global_Control state.
  bool freeze_enabled_ = false;  // Freeze_Req in Set_Prm
  bool sync_enabled_ = false;
  bool freeze_mode_ = false;
  bool sync_mode_ = false;
  bool frozen_valid_ = false;
  wire::FixedBytes<kMaxData> frozen_inputs_;
  wire::FixedBytes<kMaxData> synced_outputs_;

  wire::FixedBytes<kMaxData> outputs_;
  wire::FixedBytes<kMaxData> inputs_;

  // FCB memory per requesting master (0..127) and the reply kept for a repetition.
  struct FcbMemory {
    bool valid = false;
    bool fcb = false;
  };
  std::array<FcbMemory, 128> fcb_{};
  wire::FixedBytes<kMaxFrameSize> last_reply_;
  std::uint8_t last_reply_to_ = 0xFF;
  wire::FixedBytes<kMaxFrameSize> pending_reply_;
  std::optional<link::TimePoint> reply_due_;

  bool silent_ = false;
  Counters counters_;
};

}  // namespace cellctl::profibus

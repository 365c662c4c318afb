#pragma once
// What a DP slave device adds to the generic DP-V0 slave: it judges parameters and configuration,
// supplies its extended diagnosis and exchanges cyclic data. DpSlave does the FDL/DP protocol and
// the standard diagnosis bits; the device (e.g. encoder::Emulator) implements this interface.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace cellctl::profibus {

// The device's answer to Set_Prm. `reason` names the rule that was broken (static text: it is kept
// by DpSlave and shown by tests and traces, never sent on the wire — DP has no field for it).
struct PrmVerdict {
  bool ok = true;
  std::string_view reason;
};

enum class LeaveReason : std::uint8_t {
  watchdog,       // the master went silent longer than the response watchdog
  new_prm,        // a new Set_Prm (re-parameterisation) arrived
  cfg_rejected,   // a Chk_Cfg was refused
  address_change  // Set_Slave_Add moved the slave
};

class SlaveBehaviour {
 public:
  virtual ~SlaveBehaviour() = default;

  // User_Prm_Data: Set_Prm octet 8 onwards (the 7 standard octets are checked by DpSlave).
  virtual PrmVerdict check_prm(std::span<const std::uint8_t> user_prm) = 0;
  // The Chk_Cfg identifier bytes; false sets Cfg_Fault and keeps the slave out of data exchange.
  virtual bool check_cfg(std::span<const std::uint8_t> cfg) = 0;
  // The configuration reported by Get_Cfg; 0 (the default) reports the last accepted Chk_Cfg bytes.
  virtual std::size_t real_cfg(std::span<std::uint8_t> /*out*/) { return 0; }
  // The extended diagnosis (octet 7 onwards); 0 octets when the device has none. Called when the
  // master reads the diagnosis, so a device may clear what diag_pending() reports here.
  virtual std::size_t ext_diag(std::span<std::uint8_t> out) = 0;
  // One Data_Exchange: consume the outputs, write the inputs, return the input length.
  virtual std::size_t exchange(std::span<const std::uint8_t> outputs, std::span<std::uint8_t> inputs) = 0;
  // True while a diagnosis is waiting for the master: Data_Exchange replies carry DH (and the
  // standard diagnosis Ext_Diag) until it is read.
  virtual bool diag_pending() { return false; }
  // True while the device is not able to exchange data for a reason of its own (Stat_Diag).
  virtual bool static_diag() { return false; }

  // Lifecycle notifications.
  virtual void on_data_exchange_entered() {}
  virtual void on_data_exchange_left(LeaveReason /*reason*/) {}
  // The response watchdog expired (also reported through on_data_exchange_left(watchdog) when the
  // slave was in data exchange). A device puts its outputs in the safe state here.
  virtual void on_watchdog_expired() {}
  // Set_Slave_Add accepted: a real device stores the new address in non-volatile memory.
  virtual void on_address_changed(std::uint8_t /*new_address*/, bool /*no_add_chg*/) {}
  // Global_Control Clear_Data: outputs to the safe state (the next exchange also sees zero outputs).
  virtual void on_clear_data() {}
};

}  // namespace cellctl::profibus

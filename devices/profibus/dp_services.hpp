#pragma once
// The data units of the DP-V0 services other than diagnosis: the standard part of Set_Prm, the
// Global_Control command and Set_Slave_Add. Pure encode/decode, big-endian where multi-octet.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace cellctl::profibus {

// Set_Prm octets 1..7; the User_Prm_Data (octet 8 onwards) follows and belongs to the device profile.
inline constexpr std::size_t kPrmStandardSize = 7;

struct PrmStandard {
  // octet 1 station status
  bool lock_req = true;  // the master locks the slave for itself (with unlock_req false)
  bool unlock_req = false;
  bool sync_req = false;  // the slave shall support Sync (else Not_Supported / Prm_Fault)
  bool freeze_req = false;
  bool wd_on = true;
  std::uint8_t wd_fact_1 = 1;  // response watchdog = 10 ms × wd_fact_1 × wd_fact_2
  std::uint8_t wd_fact_2 = 1;
  std::uint8_t min_tsdr_bits = 11;  // the slave waits at least this many bit times before a reply
  std::uint16_t ident = 0;
  std::uint8_t group = 0;  // group membership bits for Global_Control

  friend bool operator==(const PrmStandard&, const PrmStandard&) = default;
};

// Writes the 7 standard octets; returns 7, or 0 when out is too small.
[[nodiscard]] std::size_t encode(const PrmStandard& prm, std::span<std::uint8_t> out) noexcept;
[[nodiscard]] std::optional<PrmStandard> decode_prm_standard(std::span<const std::uint8_t> bytes) noexcept;

// Global_Control (SAP 58, usually broadcast with SDN): octet 1 the control command, octet 2 the group
// select (0 = all slaves).
enum class GlobalCommand : std::uint8_t {
  clear_data = 0x02,  // outputs to their safe (zero) state
  unfreeze = 0x04,
  freeze = 0x08,
  unsync = 0x10,
  sync = 0x20,
};

inline constexpr std::size_t kGlobalControlSize = 2;

struct GlobalControl {
  std::uint8_t command = 0;  // OR of GlobalCommand bits
  std::uint8_t group_select = 0;
  [[nodiscard]] bool has(GlobalCommand c) const noexcept {
    return (command & static_cast<std::uint8_t>(c)) != 0;
  }
  friend bool operator==(const GlobalControl&, const GlobalControl&) = default;
};

[[nodiscard]] std::size_t encode(const GlobalControl& gc, std::span<std::uint8_t> out) noexcept;
[[nodiscard]] std::optional<GlobalControl> decode_global_control(
    std::span<const std::uint8_t> bytes) noexcept;

// Set_Slave_Add (SAP 55): new address, ident number, No_Add_Chg (1: no further change allowed).
inline constexpr std::size_t kSetSlaveAddSize = 4;

struct SetSlaveAdd {
  std::uint8_t new_address = 0;
  std::uint16_t ident = 0;
  bool no_add_chg = false;
  friend bool operator==(const SetSlaveAdd&, const SetSlaveAdd&) = default;
};

[[nodiscard]] std::size_t encode(const SetSlaveAdd& req, std::span<std::uint8_t> out) noexcept;
[[nodiscard]] std::optional<SetSlaveAdd> decode_set_slave_add(std::span<const std::uint8_t> bytes) noexcept;

}  // namespace cellctl::profibus

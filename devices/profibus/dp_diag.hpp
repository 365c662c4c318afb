#pragma once
// The DP-V0 slave diagnosis: the six standard octets as typed bits, and the extended part kept raw
// because only the device profile (e.g. the encoder profile) knows what it means.
//
//   octet 1 station status 1: 0 Station_Non_Existent (set by the master), 1 Station_Not_Ready,
//           2 Cfg_Fault, 3 Ext_Diag, 4 Not_Supported, 5 Invalid_Slave_Response (master), 6 Prm_Fault,
//           7 Master_Lock
//   octet 2 station status 2: 0 Prm_Req, 1 Stat_Diag, 2 always 1, 3 WD_On, 4 Freeze_Mode,
//           5 Sync_Mode, 7 Deactivated (master)
//   octet 3 station status 3: 7 Ext_Diag_Overflow
//   octet 4 master address (0xFF: not parameterised by any master)
//   octets 5-6 ident number, big-endian
//   octets 7.. extended diagnosis

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "profibus/fdl_frame.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::profibus {

inline constexpr std::size_t kStandardDiagSize = 6;
inline constexpr std::size_t kMaxExtDiag = kMaxData - kStandardDiagSize;
inline constexpr std::uint8_t kNoMaster = 0xFF;

struct StandardDiag {
  // station status 1
  bool station_non_existent = false;
  bool station_not_ready = false;
  bool cfg_fault = false;
  bool ext_diag = false;
  bool not_supported = false;
  bool invalid_slave_response = false;
  bool prm_fault = false;
  bool master_lock = false;
  // station status 2
  bool prm_req = false;
  bool stat_diag = false;
  bool wd_on = false;
  bool freeze_mode = false;
  bool sync_mode = false;
  bool deactivated = false;
  // station status 3
  bool ext_diag_overflow = false;

  std::uint8_t master_address = kNoMaster;
  std::uint16_t ident = 0;

  // Ready for data exchange as the standard reads it: parameterised, configured, nothing static.
  [[nodiscard]] bool ready_for_data_exchange() const noexcept {
    return !station_not_ready && !cfg_fault && !prm_fault && !prm_req && !stat_diag && !not_supported;
  }
  friend bool operator==(const StandardDiag&, const StandardDiag&) = default;
};

// Writes the 6 standard octets (octet 2 bit 2 always set); returns 6, or 0 when out is too small.
[[nodiscard]] std::size_t encode(const StandardDiag& diag, std::span<std::uint8_t> out) noexcept;
// Reads the 6 standard octets; nullopt when fewer than 6 are given.
[[nodiscard]] std::optional<StandardDiag> decode_standard_diag(std::span<const std::uint8_t> bytes) noexcept;

// The standard diagnosis in words, for fault reasons and terminals: the bits that are set by their
// names in the standard, the master that holds the slave and its ident number, e.g.
// "Station_Not_Ready Prm_Fault Prm_Req, master none, ident 0x0C88". Inline buffer: no allocation.
struct DiagText {
  std::array<char, 192> chars{};
  std::size_t size = 0;
  [[nodiscard]] std::string_view view() const noexcept { return {chars.data(), size}; }
};
[[nodiscard]] DiagText describe(const StandardDiag& diag) noexcept;

// A whole Slave_Diag reply: standard part typed, extended part (octet 7 onwards) raw.
struct DpDiagnosis {
  StandardDiag standard;
  wire::FixedBytes<kMaxExtDiag> extended;
  friend bool operator==(const DpDiagnosis&, const DpDiagnosis&) = default;
};

[[nodiscard]] std::optional<DpDiagnosis> decode_diagnosis(std::span<const std::uint8_t> bytes) noexcept;

}  // namespace cellctl::profibus

#pragma once
// The numbers of PROFIBUS FDL and DP-V0 that appear on the wire: function codes (FC), service access
// points (SAP) and special addresses. Named once here so that codec, master and slave never spell a
// bare 0x6d.

#include <cstdint>

namespace cellctl::profibus {

// Station addresses. 126 is the commissioning address (only Set_Slave_Add is served there), 127 is
// the broadcast address (SDN only, no reply).
inline constexpr std::uint8_t kMaxMasterAddress = 125;
inline constexpr std::uint8_t kDefaultSlaveAddress = 126;
inline constexpr std::uint8_t kBroadcastAddress = 127;
// Bit 7 of DA (SA) says that a DSAP (SSAP) octet leads the data unit.
inline constexpr std::uint8_t kAddressExtension = 0x80;

namespace fc {
// Request frames: bit 6 set; FCB/FCV guard against executing a repeated request twice.
inline constexpr std::uint8_t kRequest = 0x40;
inline constexpr std::uint8_t kFcb = 0x20;  // frame count bit, toggled per new request to a station
inline constexpr std::uint8_t kFcv = 0x10;  // frame count bit valid
inline constexpr std::uint8_t kFunctionMask = 0x0F;
inline constexpr std::uint8_t kSdnLow = 0x04;   // send data, no acknowledge, low priority
inline constexpr std::uint8_t kSdnHigh = 0x06;  // send data, no acknowledge, high priority
inline constexpr std::uint8_t kFdlStatus = 0x09;
inline constexpr std::uint8_t kSrdLow = 0x0C;  // send and request data, low priority
inline constexpr std::uint8_t kSrdHigh = 0x0D;

// Response frames: bit 6 clear; the low nibble says what happened, bits 4..5 the station type.
inline constexpr std::uint8_t kOk = 0x00;
inline constexpr std::uint8_t kUserError = 0x01;     // UE
inline constexpr std::uint8_t kNoResource = 0x02;    // RR
inline constexpr std::uint8_t kNotActivated = 0x03;  // RS: service (SAP) not activated
inline constexpr std::uint8_t kDataLow = 0x08;       // DL: reply data, nothing else to report
inline constexpr std::uint8_t kNoResponse = 0x09;    // NR
inline constexpr std::uint8_t kDataHigh = 0x0A;      // DH: reply data, and a diagnosis is pending
inline constexpr std::uint8_t kStationTypeMask = 0x30;
inline constexpr std::uint8_t kStationSlave = 0x00;
inline constexpr std::uint8_t kStationMasterNotReady = 0x10;
inline constexpr std::uint8_t kStationMasterReady = 0x20;
inline constexpr std::uint8_t kStationMasterInRing = 0x30;

[[nodiscard]] constexpr bool is_request(std::uint8_t code) noexcept {
  return (code & kRequest) != 0;
}
[[nodiscard]] constexpr std::uint8_t function(std::uint8_t code) noexcept {
  return code & kFunctionMask;
}
}  // namespace fc

namespace sap {
inline constexpr std::uint8_t kSetSlaveAdd = 55;
inline constexpr std::uint8_t kRdInp = 56;
inline constexpr std::uint8_t kRdOutp = 57;
inline constexpr std::uint8_t kGlobalControl = 58;
inline constexpr std::uint8_t kGetCfg = 59;
inline constexpr std::uint8_t kSlaveDiag = 60;
inline constexpr std::uint8_t kSetPrm = 61;
inline constexpr std::uint8_t kChkCfg = 62;
// A DP master sends all its SAP requests from SSAP 62.
inline constexpr std::uint8_t kMaster = 62;
}  // namespace sap

}  // namespace cellctl::profibus

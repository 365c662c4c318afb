#pragma once
// FDL frames (PROFIBUS layer 2) as typed values, and the pure encode/parse between them and bytes.
//
//   SD1  10 DA SA FC FCS 16                      no data unit
//   SD2  68 LE LEr 68 DA SA FC [DSAP SSAP] DU FCS 16   LE = count of DA..DU, 4..249
//   SD3  A2 DA SA FC DU(8) FCS 16                exactly 8 data-unit octets (SAPs included)
//   SD4  DC DA SA                                token
//   SC   E5                                      short acknowledge
//
// FCS = sum of DA..DU (inclusive) mod 256. A sender must use SD3 for an 8-octet data unit, so a
// receiver parses both SD2 and SD3. No allocation, no I/O, bad bytes give a typed error.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "wire/fixed_bytes.hpp"

namespace cellctl::profibus {

inline constexpr std::uint8_t kSd1 = 0x10;
inline constexpr std::uint8_t kSd2 = 0x68;
inline constexpr std::uint8_t kSd3 = 0xA2;
inline constexpr std::uint8_t kSd4 = 0xDC;
inline constexpr std::uint8_t kShortAck = 0xE5;
inline constexpr std::uint8_t kEndDelimiter = 0x16;

inline constexpr std::size_t kSd3DataUnit = 8;
inline constexpr std::size_t kMinSd2Length = 4;    // LE: DA SA FC + at least one DU octet
inline constexpr std::size_t kMaxSd2Length = 249;  // LE
// The longest data unit after the SAPs (249 - DA SA FC - DSAP SSAP).
inline constexpr std::size_t kMaxData = kMaxSd2Length - 5;
// The longest frame on the wire: SD2 with LE 249 (4 header + 249 + FCS + ED).
inline constexpr std::size_t kMaxFrameSize = 4 + kMaxSd2Length + 2;

enum class FrameKind : std::uint8_t { sd1, sd2, sd3, token, short_ack };

[[nodiscard]] std::string_view to_string(FrameKind k) noexcept;

struct FdlFrame {
  // On parse: the frame type seen. On encode: only token/short_ack are taken from here; for data
  // frames encode() picks SD1/SD2/SD3 from the data-unit length, as the standard requires.
  FrameKind kind = FrameKind::sd1;
  std::uint8_t da = 0;  // destination address 0..127, without the extension bit
  std::uint8_t sa = 0;  // source address 0..127, without the extension bit
  std::uint8_t fc = 0;
  std::optional<std::uint8_t> dsap;  // present ⇔ extension bit on DA
  std::optional<std::uint8_t> ssap;  // present ⇔ extension bit on SA
  wire::FixedBytes<kMaxData> data;   // the data unit after the SAPs

  // Octets of the data unit including the SAPs (what decides SD1/SD2/SD3).
  [[nodiscard]] std::size_t data_unit_size() const noexcept {
    return data.size() + (dsap ? 1u : 0u) + (ssap ? 1u : 0u);
  }
  friend bool operator==(const FdlFrame&, const FdlFrame&) = default;
};

// Frames as they are built by masters and slaves.
[[nodiscard]] FdlFrame make_frame(std::uint8_t da, std::uint8_t sa, std::uint8_t fc,
                                  std::span<const std::uint8_t> data = {}) noexcept;
[[nodiscard]] FdlFrame make_sap_frame(std::uint8_t da, std::uint8_t sa, std::uint8_t fc, std::uint8_t dsap,
                                      std::uint8_t ssap, std::span<const std::uint8_t> data = {}) noexcept;
[[nodiscard]] FdlFrame make_short_ack() noexcept;

// Writes the frame into out; returns the octet count, 0 when out is too small or the frame cannot be
// represented (address > 127, data unit > 246 octets).
[[nodiscard]] std::size_t encode(const FdlFrame& frame, std::span<std::uint8_t> out) noexcept;

// The octet count encode() would produce (0 when it cannot).
[[nodiscard]] std::size_t encoded_size(const FdlFrame& frame) noexcept;

enum class FdlError : std::uint8_t {
  none,
  garbage,            // octets before a start delimiter, skipped
  bad_length,         // SD2 LE outside 4..249
  length_mismatch,    // SD2 LE != LEr, or the second 68 missing
  bad_fcs,            // frame check sequence wrong
  bad_end_delimiter,  // no 16 where the frame should end
  bad_sap,            // extension bit set but no octet left for the SAP
  data_too_long,      // more data octets after the SAPs than DP allows (244): refused, never cut
};

[[nodiscard]] std::string_view to_string(FdlError e) noexcept;

// The result of parsing the front of a byte buffer.
struct FdlParse {
  enum class Status : std::uint8_t { frame, need_more, error } status = Status::need_more;
  FdlError error = FdlError::none;
  // Octets to drop from the front: the frame (status frame), or the octets that are known bad
  // (status error; the parser resynchronises on the next start delimiter).
  std::size_t consumed = 0;
  FdlFrame frame;
};

// Parses the frame at the front of bytes (garbage before a start delimiter is reported as such).
// A frame is taken whole or refused with a typed error: an LE outside 4..249, or a data unit whose
// data (after the SAPs) exceed the 244 octets DP allows (an SD2 with LE 249 and no SAPs carries 246),
// is an error, never a shortened frame.
[[nodiscard]] FdlParse parse_frame(std::span<const std::uint8_t> bytes) noexcept;

}  // namespace cellctl::profibus

#pragma once
// The e@syDrive's RS232 framing (manual chapter 4): STX, then ASCII hex pairs for VER, MSGID, LEN,
// DATA… and CHK, then ETX. Pure functions over caller buffers: no I/O, no clock, no allocation, and
// bad bytes come back as typed errors. Sessions and the emulator share this one codec.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "spindle/message.hpp"

namespace cellctl::spindle {

inline constexpr std::uint8_t kStx = 0x02;
inline constexpr std::uint8_t kEtx = 0x03;
inline constexpr std::uint8_t kVersion = 0x01;
inline constexpr std::size_t kMaxDataLength = 27;  // RES 0x59, the longest message
// The text between STX and ETX: VER, MSGID, LEN, DATA, CHK, two characters per byte.
inline constexpr std::size_t kMaxTextLength = 2 * (3 + kMaxDataLength + 1);
inline constexpr std::size_t kMaxFrameLength = 1 + kMaxTextLength + 1;

enum class DecodeError : std::uint8_t {
  none,
  bad_hex_digit,    // a character other than '0'..'9', 'a'..'f' between STX and ETX
  bad_version,      // VER is not 01
  unknown_message,  // a MSGID the manual does not define
  wrong_length,     // LEN does not match the MSGID, or ETX came early
  missing_etx,      // the text had its full length and the next byte was not ETX
  interrupted,      // an STX arrived inside a frame: the frame was cut off, the new one is kept
  bad_checksum,     // CHK does not match the text
  bad_value,        // a well-formed frame with a field value the manual does not define
};
[[nodiscard]] std::string_view to_string(DecodeError e) noexcept;

// What a finished frame decoded to: a message, or the reason it was rejected.
struct Decoded {
  DecodeError error = DecodeError::none;
  Message message{};
  [[nodiscard]] bool ok() const noexcept { return error == DecodeError::none; }
};

class Codec {
 public:
  // The checksum of the text between STX and CHK: the low byte of the sum of its ASCII codes. (The
  // manual's worked examples all follow this; its formula "VER+MSGID+LEN+DATA" over bytes does not.)
  [[nodiscard]] static std::uint8_t checksum(std::span<const std::uint8_t> text) noexcept;

  // Writes the whole frame STX…ETX into `out`; returns its length, or 0 when `out` is too small.
  [[nodiscard]] static std::size_t encode(const Message& message, std::span<std::uint8_t> out) noexcept;

  // Decodes the DATA of a message whose frame was already checked.
  [[nodiscard]] static Decoded decode_data(std::uint8_t id, std::span<const std::uint8_t> data) noexcept;

  // Decodes exactly one frame STX…ETX (tests and tools; the line uses FrameDecoder).
  [[nodiscard]] static Decoded decode_frame(std::span<const std::uint8_t> frame) noexcept;
};

// Cuts a byte stream into frames. Bytes outside a frame are skipped (counted); after any error it
// waits for the next STX, so one corrupt telegram never costs the next one.
class FrameDecoder {
 public:
  // Takes one byte; returns the outcome when a frame ended (or broke off), nullopt while none did.
  [[nodiscard]] std::optional<Decoded> push(std::uint8_t byte) noexcept;
  void reset() noexcept;
  // Bytes seen outside any frame since construction: line noise or the tail of a rejected frame.
  [[nodiscard]] std::uint64_t skipped_bytes() const noexcept { return skipped_; }

 private:
  [[nodiscard]] std::optional<Decoded> fail(DecodeError e) noexcept;
  [[nodiscard]] std::optional<Decoded> check_header() noexcept;
  [[nodiscard]] Decoded finish() const noexcept;

  std::array<std::uint8_t, kMaxTextLength> text_{};
  std::size_t size_ = 0;
  std::size_t expected_size_ = 0;  // known once the header (VER, MSGID, LEN) is in; 0 before
  bool in_frame_ = false;
  std::uint64_t skipped_ = 0;
};

}  // namespace cellctl::spindle

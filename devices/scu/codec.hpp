#pragma once
// SCU telegrams ⇄ typed messages. Pure functions over spans: no I/O, no clock, no allocation, and bad
// bytes give a typed DecodeError, never an exception.
//
//   request: 'R' <Y> <parameters…> crc_lo crc_hi
//   reply:   'R' <Y> <status> [ctp_lo ctp_hi data…] crc_lo crc_hi
//
// RT and RC requests carry ctp (bytes that follow it, before the CRC); the other requests have fixed
// lengths. A reply carries ctp only when it is an ACK with data (RG, and RC with a cyclic object);
// so decoding a reply needs to know which request it answers (ReplyShape).

#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "scu/protocol.hpp"

namespace cellctl::scu {

struct OpenRequest {  // RO
  std::uint8_t safety_id = 0;
};
struct AbortRequest {};                        // RA
struct CyclicRequest {                         // RC
  std::uint8_t index = kNoCyclicObject;        // 0..4 = CyclicObj 1..5
  std::span<const std::uint8_t> write_data{};  // the cyclic object's write data, in ID order
};
struct GetRequest {  // RG
  std::uint16_t data_id = 0;
};
struct TransferRequest {  // RT
  std::uint16_t data_id = 0;
  std::span<const std::uint8_t> value{};
};
struct ExecuteRequest {                    // RE
  std::uint8_t function = 0;               // fnc_ID: 0..9 = F1..F10, 19 = F20 …
  std::uint8_t direction = kUnusedParam;   // para_ID[0]: Direction for F1..F10
  std::uint8_t start_stop = kUnusedParam;  // para_ID[1]: 0 fast, 1 soft, 0xFF configured
};
struct StopRequest {  // RS
  std::uint8_t function = 0;
  std::uint8_t mode = kUnusedParam;  // 0 fast, 1 soft, 0xFF configured
};

using Request = std::variant<OpenRequest, AbortRequest, CyclicRequest, GetRequest, TransferRequest,
                             ExecuteRequest, StopRequest>;

[[nodiscard]] Command command_of(const Request& r) noexcept;

struct Reply {
  Command command = Command::get;  // may hold a byte that is no Command (an ICE for an unknown <Y>)
  Status status = Status::ack;
  bool has_data = false;                 // carries ctp + data (ACK to RG, or to RC with a cyclic object)
  std::span<const std::uint8_t> data{};  // valid as long as the decoded bytes are
};

// What the reply to a request looks like on an ACK.
struct ReplyShape {
  Command command = Command::get;
  bool has_data = false;
  friend bool operator==(const ReplyShape&, const ReplyShape&) = default;
};
[[nodiscard]] ReplyShape reply_shape(const Request& r) noexcept;

enum class DecodeError : std::uint8_t {
  none,
  bad_start,           // the first byte is not 'R' (garbage)
  unknown_command,     // <Y> is no SCU command
  unexpected_command,  // a well-formed command, but not the one in flight
  bad_status,          // the status byte is neither ACK nor one of the five errors
  bad_length,          // ctp impossible (too big, too small for the command) or frame length wrong
  bad_crc,
};
[[nodiscard]] const char* to_string(DecodeError e) noexcept;

template <class T>
struct Decoded {
  T value{};
  DecodeError error = DecodeError::none;
  [[nodiscard]] bool ok() const noexcept { return error == DecodeError::none; }
};

// Encoders write a complete telegram (CRC included) into `out`; false when it does not fit or a
// field is out of what the wire can carry (nothing useful is left in `out` then).
[[nodiscard]] bool encode_request(const Request& r, RequestBytes& out) noexcept;
[[nodiscard]] bool encode_reply(const Reply& r, ReplyBytes& out) noexcept;

// Decoders take exactly one complete frame.
[[nodiscard]] Decoded<Request> decode_request(std::span<const std::uint8_t> frame) noexcept;
[[nodiscard]] Decoded<Reply> decode_reply(std::span<const std::uint8_t> frame, ReplyShape expected) noexcept;

// Framing from a prefix of received bytes: how long the telegram starting at prefix[0] is, once enough
// of it is there to tell. `length` 0 with no error = need more bytes.
struct FrameLength {
  std::size_t length = 0;
  DecodeError error = DecodeError::none;
};
[[nodiscard]] FrameLength request_frame_length(std::span<const std::uint8_t> prefix) noexcept;
[[nodiscard]] FrameLength reply_frame_length(std::span<const std::uint8_t> prefix,
                                             ReplyShape expected) noexcept;

// True when the frame's last two bytes are the CRC of the rest (low byte first).
[[nodiscard]] bool crc_ok(std::span<const std::uint8_t> frame) noexcept;

}  // namespace cellctl::scu

#pragma once
// The SCU RS232 protocol's vocabulary: command and status bytes, the limits that size every buffer,
// and the manual's timing rules. Shared by codec, session and emulator.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "wire/fixed_bytes.hpp"

namespace cellctl::scu {

// Every telegram starts with the major command byte 'R'; the minor byte names the command.
inline constexpr std::uint8_t kMajor = 'R';

enum class Command : std::uint8_t {
  get = 'G',       // RG remote data get
  transfer = 'T',  // RT remote data transfer (write a 0x3xxx element)
  cyclic = 'C',    // RC remote cyclic (the watchdog keep-alive, optionally with a cyclic object)
  execute = 'E',   // RE remote execute function
  stop = 'S',      // RS remote stop function
  open = 'O',      // RO remote mode open
  abort = 'A',     // RA remote mode abort (back to normal mode)
};

enum class Status : std::uint8_t {
  ack = 0x06,
  checksum_error = 0x80,         // CSE
  parameter_data_error = 0x81,   // PDE
  parameter_count_error = 0x82,  // PCE
  invalid_command = 0x83,        // ICE
  permission_error = 0x84,       // PE
};

[[nodiscard]] std::optional<Command> command_from_byte(std::uint8_t b) noexcept;
[[nodiscard]] std::optional<Status> status_from_byte(std::uint8_t b) noexcept;
// "RG", "RT" … ("R?" for a byte that is no command).
[[nodiscard]] std::string_view to_string(Command c) noexcept;
// "ACK", "CSE", "PDE", "PCE", "ICE", "PE".
[[nodiscard]] std::string_view to_string(Status s) noexcept;
// What the status means, in words for an operator.
[[nodiscard]] std::string_view describe(Status s) noexcept;

// "-1" in the manual's tables: an unused parameter byte / data ID.
inline constexpr std::uint8_t kUnusedParam = 0xFF;
inline constexpr std::uint16_t kUnusedDataId = 0xFFFF;
// RC's index byte when no cyclic object is exchanged.
inline constexpr std::uint8_t kNoCyclicObject = 0xFF;
inline constexpr int kCyclicObjectCount = 5;  // CyclicObj 1..5, RC index 0..4

inline constexpr int kActuatorCount = 6;
inline constexpr int kMotionFunctionCount = 10;        // F1..F10, fnc_ID 0..9
inline constexpr std::uint8_t kEmergencyStopFnc = 19;  // F20
inline constexpr std::uint8_t kBuzzerFnc = 10;         // F11
inline constexpr std::uint8_t kBinaryOutput1Fnc = 16;  // F17
inline constexpr std::uint8_t kBinaryOutput2Fnc = 17;  // F18
inline constexpr std::uint8_t kLed1Fnc = 20;           // F21
inline constexpr std::uint8_t kLed2Fnc = 21;           // F22

// RE's motion_direction (para_ID[0]) for F1..F10.
enum class Direction : std::uint8_t {
  none = 0,
  in = 1,
  out = 2,
  memory1 = 3,
  memory2 = 4,
  memory3 = 5,
  memory4 = 6,
  intermediate_in = 7,
  intermediate_out = 8,
  remote_position = 9,
};
// RE's para_ID[1] and RS's mode.
inline constexpr std::uint8_t kFastStartStop = 0;
inline constexpr std::uint8_t kSoftStartStop = 1;

// Buffer sizes. A request's ctp is at most an RC carrying six 24-byte write elements (150 B);
// a reply's data is at most RG 0x2000, six 104-byte position structures (624 B).
inline constexpr std::size_t kMaxRequestData = 150;
inline constexpr std::size_t kMaxRequestTelegram = 4 + kMaxRequestData + 2;
inline constexpr std::size_t kMaxReplyData = 640;
inline constexpr std::size_t kMaxReplyTelegram = 5 + kMaxReplyData + 2;
using RequestBytes = wire::FixedBytes<kMaxRequestTelegram>;
using ReplyBytes = wire::FixedBytes<kMaxReplyTelegram>;

// The manual's timing: RC at least every 500 ms or the SCU's watchdog ends remote mode's motions;
// a gap of more than 1000 ms between the bytes of one telegram discards it; the SCU answers within
// 2000 ms at most.
inline constexpr std::chrono::milliseconds kWatchdogPeriod{500};
inline constexpr std::chrono::milliseconds kInterByteTimeout{1000};
inline constexpr std::chrono::milliseconds kMaxReplyDelay{2000};

}  // namespace cellctl::scu

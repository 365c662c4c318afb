#pragma once
// The device side's receive path (the emulator's): bytes in with their arrival time, whole requests
// out, framed from the fixed lengths and ctp of the commands. A partial request older than the
// manual's inter-byte time-out (1000 ms) is discarded, as the SCU does. Errors carry the command byte
// when it is known, so that the caller can answer CSE/PCE/ICE for the right command.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "link/clock.hpp"
#include "scu/codec.hpp"
#include "wire/frame_buffer.hpp"

namespace cellctl::scu {

class RequestStream {
 public:
  struct Event {
    enum class Kind : std::uint8_t { need_more, request, error };
    Kind kind = Kind::need_more;
    Request request{};                      // kind == request; spans point into the stream
    DecodeError error = DecodeError::none;  // kind == error
    std::uint8_t command_byte = 0;          // the <Y> of the broken telegram, 0 when there was none
    std::size_t dropped = 0;
  };

  explicit RequestStream(link::Duration inter_byte_timeout = kInterByteTimeout) noexcept
      : timeout_(inter_byte_timeout) {}

  // Discards a partial request whose last byte came longer than the inter-byte time-out before `now`;
  // returns how many bytes were discarded.
  std::size_t expire(link::TimePoint now) noexcept;
  std::size_t feed(std::span<const std::uint8_t> bytes, link::TimePoint now) noexcept;
  [[nodiscard]] Event next() noexcept;
  [[nodiscard]] std::size_t buffered() const noexcept { return buffer_.size(); }

 private:
  wire::FrameBuffer<2 * kMaxRequestTelegram> buffer_;
  link::Duration timeout_;
  link::TimePoint last_byte_at_{};
};

}  // namespace cellctl::scu

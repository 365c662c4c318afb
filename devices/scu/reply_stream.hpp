#pragma once
// The master side's receive path: bytes in as they come from the link, whole replies out, framed from
// the status byte and ctp of the reply to the request in flight. Garbage before a reply, a reply to
// another command, an impossible ctp or a bad CRC each come out as one typed error event and the
// stream resynchronises on the next 'R'. Never throws, never allocates.

#include <cstddef>
#include <cstdint>
#include <span>

#include "scu/codec.hpp"
#include "wire/frame_buffer.hpp"

namespace cellctl::scu {

class ReplyStream {
 public:
  struct Event {
    enum class Kind : std::uint8_t { need_more, reply, error };
    Kind kind = Kind::need_more;
    Reply reply{};                          // kind == reply; its data points into the stream
    DecodeError error = DecodeError::none;  // kind == error
    std::size_t dropped = 0;                // bytes discarded by this error
  };

  // A request was sent: expect its reply. Whatever was received before belongs to nothing (half-duplex,
  // one request in flight) and is discarded.
  void expect(ReplyShape shape) noexcept;
  // No request in flight: anything that arrives now is garbage.
  void expect_nothing() noexcept;
  // Takes what fits (the buffer holds two maximal replies); returns how many bytes were taken.
  std::size_t feed(std::span<const std::uint8_t> bytes) noexcept;
  // The next complete reply or error; a reply's data stays valid until the next call of any method.
  [[nodiscard]] Event next() noexcept;
  [[nodiscard]] std::size_t buffered() const noexcept { return buffer_.size(); }

 private:
  wire::FrameBuffer<2 * kMaxReplyTelegram> buffer_;
  ReplyShape shape_{};
  bool expecting_ = false;
};

}  // namespace cellctl::scu

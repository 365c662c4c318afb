#pragma once
// A stream of received octets cut into FDL frames: bytes arrive in any pieces, frames or typed errors
// come out. Errors resynchronise on the next start delimiter, so garbage and torn frames cost only
// themselves. Inline buffer, no allocation.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "profibus/fdl_frame.hpp"
#include "wire/byte_queue.hpp"

namespace cellctl::profibus {

struct FdlEvent {
  FdlError error = FdlError::none;  // none: frame is valid
  FdlFrame frame;
};

class FdlDecoder {
 public:
  // Appends received octets; returns how many fit (the buffer holds two maximum frames).
  std::size_t push(std::span<const std::uint8_t> bytes) noexcept;
  // The next frame or error found in the buffered octets; nullopt when more octets are needed.
  [[nodiscard]] std::optional<FdlEvent> next() noexcept;
  // Forgets a partial frame (the line went idle, or a new request makes old octets meaningless).
  void reset() noexcept { buffer_.clear(); }
  [[nodiscard]] std::size_t buffered() const noexcept { return buffer_.size(); }

 private:
  wire::ByteQueue<2 * kMaxFrameSize> buffer_;
};

}  // namespace cellctl::profibus

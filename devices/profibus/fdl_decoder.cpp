#include "profibus/fdl_decoder.hpp"

#include <array>

namespace cellctl::profibus {

std::size_t FdlDecoder::push(std::span<const std::uint8_t> bytes) noexcept {
  return buffer_.push(bytes);
}

std::optional<FdlEvent> FdlDecoder::next() noexcept {
  if (buffer_.empty()) return std::nullopt;
  // parse_frame works on contiguous octets; the longest frame is copied out of the ring (on the
  // stack, no allocation).
  std::array<std::uint8_t, kMaxFrameSize> window{};
  const std::size_t n = std::min(buffer_.size(), window.size());
  for (std::size_t i = 0; i < n; ++i) window[i] = buffer_[i];
  FdlParse p = parse_frame(std::span<const std::uint8_t>(window.data(), n));
  if (p.status == FdlParse::Status::need_more) return std::nullopt;
  buffer_.drop(p.consumed);
  FdlEvent ev;
  ev.error = p.status == FdlParse::Status::error ? p.error : FdlError::none;
  ev.frame = p.frame;
  return ev;
}

}  // namespace cellctl::profibus

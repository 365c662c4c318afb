#include "scu/request_stream.hpp"

#include <algorithm>

namespace cellctl::scu {

std::size_t RequestStream::expire(link::TimePoint now) noexcept {
  buffer_.release();
  if (buffer_.size() == 0 || now - last_byte_at_ <= timeout_) return 0;
  const auto n = buffer_.size();
  buffer_.clear();
  return n;
}

std::size_t RequestStream::feed(std::span<const std::uint8_t> bytes, link::TimePoint now) noexcept {
  // Stale bytes never join new ones. (A caller that counts what expires calls expire() itself
  // first, as the emulator does; here there is nothing left to count.)
  (void)expire(now);
  if (bytes.empty()) return 0;
  last_byte_at_ = now;
  return buffer_.feed(bytes);
}

RequestStream::Event RequestStream::next() noexcept {
  buffer_.release();
  const auto bytes = buffer_.view();
  if (bytes.empty()) return {};
  if (bytes[0] != kMajor) {
    const auto it = std::find(bytes.begin(), bytes.end(), kMajor);
    const auto n = static_cast<std::size_t>(it - bytes.begin());
    buffer_.drop(n);
    return {Event::Kind::error, {}, DecodeError::bad_start, 0, n};
  }
  const auto len = request_frame_length(bytes);
  if (len.error != DecodeError::none) {
    // An unknown command or an impossible ctp: its length cannot be known, so everything received
    // so far goes; the answer (ICE/PCE) names the command byte.
    const std::uint8_t y = bytes.size() > 1 ? bytes[1] : 0;
    const auto n = bytes.size();
    buffer_.clear();
    return {Event::Kind::error, {}, len.error, y, n};
  }
  if (len.length == 0 || bytes.size() < len.length) return {};
  const auto frame = bytes.first(len.length);
  const auto decoded = decode_request(frame);
  buffer_.hand_out(len.length);
  if (!decoded.ok()) return {Event::Kind::error, {}, decoded.error, frame[1], len.length};
  return {Event::Kind::request, decoded.value, DecodeError::none, frame[1], 0};
}

}  // namespace cellctl::scu

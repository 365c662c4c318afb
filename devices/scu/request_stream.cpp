#include "scu/request_stream.hpp"

#include <algorithm>
#include <cstring>

namespace cellctl::scu {

std::size_t RequestStream::expire(link::TimePoint now) noexcept {
  drop(consumed_);
  consumed_ = 0;
  if (size_ == 0 || now - last_byte_at_ <= timeout_) return 0;
  const auto n = size_;
  size_ = 0;
  return n;
}

std::size_t RequestStream::feed(std::span<const std::uint8_t> bytes, link::TimePoint now) noexcept {
  (void)expire(now);
  if (bytes.empty()) return 0;
  const std::size_t n = std::min(bytes.size(), kCapacity - size_);
  std::memcpy(buffer_ + size_, bytes.data(), n);
  size_ += n;
  last_byte_at_ = now;
  return n;
}

void RequestStream::drop(std::size_t n) noexcept {
  n = std::min(n, size_);
  std::memmove(buffer_, buffer_ + n, size_ - n);
  size_ -= n;
}

RequestStream::Event RequestStream::next() noexcept {
  drop(consumed_);
  consumed_ = 0;
  if (size_ == 0) return {};
  const std::span<const std::uint8_t> bytes(buffer_, size_);
  if (bytes[0] != kMajor) {
    const auto it = std::find(bytes.begin(), bytes.end(), kMajor);
    const auto n = static_cast<std::size_t>(it - bytes.begin());
    drop(n);
    return {Event::Kind::error, {}, DecodeError::bad_start, 0, n};
  }
  const auto len = request_frame_length(bytes);
  if (len.error != DecodeError::none) {
    // An unknown command or an impossible ctp: its length cannot be known, so everything received
    // so far goes; the answer (ICE/PCE) names the command byte.
    const std::uint8_t y = bytes.size() > 1 ? bytes[1] : 0;
    const auto n = size_;
    size_ = 0;
    return {Event::Kind::error, {}, len.error, y, n};
  }
  if (len.length == 0 || size_ < len.length) return {};
  const auto frame = bytes.first(len.length);
  const auto decoded = decode_request(frame);
  consumed_ = len.length;
  if (!decoded.ok()) return {Event::Kind::error, {}, decoded.error, frame[1], len.length};
  return {Event::Kind::request, decoded.value, DecodeError::none, frame[1], 0};
}

}  // namespace cellctl::scu

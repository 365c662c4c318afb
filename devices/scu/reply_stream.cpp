#include "scu/reply_stream.hpp"

#include <algorithm>
#include <cstring>

namespace cellctl::scu {

void ReplyStream::expect(ReplyShape shape) noexcept {
  size_ = consumed_ = 0;
  shape_ = shape;
  expecting_ = true;
}

void ReplyStream::expect_nothing() noexcept {
  drop(consumed_);
  consumed_ = 0;
  expecting_ = false;
}

std::size_t ReplyStream::feed(std::span<const std::uint8_t> bytes) noexcept {
  drop(consumed_);
  consumed_ = 0;
  const std::size_t n = std::min(bytes.size(), kCapacity - size_);
  std::memcpy(buffer_ + size_, bytes.data(), n);
  size_ += n;
  return n;
}

void ReplyStream::drop(std::size_t n) noexcept {
  n = std::min(n, size_);
  std::memmove(buffer_, buffer_ + n, size_ - n);
  size_ -= n;
}

ReplyStream::Event ReplyStream::next() noexcept {
  drop(consumed_);
  consumed_ = 0;
  if (size_ == 0) return {};
  const std::span<const std::uint8_t> bytes(buffer_, size_);
  if (!expecting_) {
    drop(size_);
    return {Event::Kind::error, {}, DecodeError::bad_start, bytes.size()};
  }
  if (bytes[0] != kMajor) {
    // Skip to the next candidate start in one event: a burst of line noise is one error, not many.
    const auto it = std::find(bytes.begin(), bytes.end(), kMajor);
    const auto n = static_cast<std::size_t>(it - bytes.begin());
    drop(n);
    return {Event::Kind::error, {}, DecodeError::bad_start, n};
  }
  const auto len = reply_frame_length(bytes, shape_);
  if (len.error != DecodeError::none) {
    drop(1);  // this 'R' started nothing valid: look for the next one
    return {Event::Kind::error, {}, len.error, 1};
  }
  if (len.length == 0 || size_ < len.length) return {};
  const auto frame = bytes.first(len.length);
  const auto decoded = decode_reply(frame, shape_);
  if (!decoded.ok()) {
    // A header that matched the request in flight and a full length of bytes: this was the reply,
    // damaged. Dropping all of it keeps its tail from being mistaken for a new start.
    drop(len.length);
    return {Event::Kind::error, {}, decoded.error, len.length};
  }
  consumed_ = len.length;
  return {Event::Kind::reply, decoded.value, DecodeError::none, 0};
}

}  // namespace cellctl::scu

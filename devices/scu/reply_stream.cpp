#include "scu/reply_stream.hpp"

#include <algorithm>

namespace cellctl::scu {

void ReplyStream::expect(ReplyShape shape) noexcept {
  buffer_.clear();
  shape_ = shape;
  expecting_ = true;
}

void ReplyStream::expect_nothing() noexcept {
  buffer_.release();
  expecting_ = false;
}

std::size_t ReplyStream::feed(std::span<const std::uint8_t> bytes) noexcept {
  return buffer_.feed(bytes);
}

ReplyStream::Event ReplyStream::next() noexcept {
  buffer_.release();
  const auto bytes = buffer_.view();
  if (bytes.empty()) return {};
  if (!expecting_) {
    const auto n = bytes.size();
    buffer_.clear();
    return {Event::Kind::error, {}, DecodeError::bad_start, n};
  }
  if (bytes[0] != kMajor) {
    // Skip to the next candidate start in one event: a burst of line noise is one error, not many.
    const auto it = std::find(bytes.begin(), bytes.end(), kMajor);
    const auto n = static_cast<std::size_t>(it - bytes.begin());
    buffer_.drop(n);
    return {Event::Kind::error, {}, DecodeError::bad_start, n};
  }
  const auto len = reply_frame_length(bytes, shape_);
  if (len.error != DecodeError::none) {
    buffer_.drop(1);  // this 'R' started nothing valid: look for the next one
    return {Event::Kind::error, {}, len.error, 1};
  }
  if (len.length == 0 || bytes.size() < len.length) return {};
  const auto decoded = decode_reply(bytes.first(len.length), shape_);
  if (!decoded.ok()) {
    // A header that matched the request in flight and a full length of bytes: this was the reply,
    // damaged. Dropping all of it keeps its tail from being mistaken for a new start.
    buffer_.drop(len.length);
    return {Event::Kind::error, {}, decoded.error, len.length};
  }
  buffer_.hand_out(len.length);
  return {Event::Kind::reply, decoded.value, DecodeError::none, 0};
}

}  // namespace cellctl::scu

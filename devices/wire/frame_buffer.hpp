#pragma once
// The receive buffer a stream framer works on: bytes appended as they arrive, whole frames handed out
// as views into it and released on the next call, the front dropped on a resynchronisation. One for
// every framer (the SCU's request and reply streams), so that none keeps its own copy of this
// bookkeeping. Never allocates; bytes beyond the capacity are refused (feed says how many were taken).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace cellctl::wire {

template <std::size_t Capacity>
class FrameBuffer {
 public:
  // Releases the frame handed out last, then appends what fits; returns how many bytes were taken.
  std::size_t feed(std::span<const std::uint8_t> bytes) noexcept {
    release();
    const std::size_t n = std::min(bytes.size(), Capacity - size_);
    if (n > 0) std::memcpy(data_.data() + size_, bytes.data(), n);
    size_ += n;
    return n;
  }
  // Drops the frame handed out last (its view is no longer needed).
  void release() noexcept {
    drop(consumed_);
    consumed_ = 0;
  }
  // The front `n` bytes are a frame the caller hands out: released at the next feed()/release().
  void hand_out(std::size_t n) noexcept { consumed_ = std::min(n, size_); }
  void drop(std::size_t n) noexcept {
    n = std::min(n, size_);
    std::memmove(data_.data(), data_.data() + n, size_ - n);
    size_ -= n;
  }
  void clear() noexcept { size_ = consumed_ = 0; }
  [[nodiscard]] std::span<const std::uint8_t> view() const noexcept { return {data_.data(), size_}; }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }

 private:
  std::array<std::uint8_t, Capacity> data_{};
  std::size_t size_ = 0;
  std::size_t consumed_ = 0;
};

}  // namespace cellctl::wire

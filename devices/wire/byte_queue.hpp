#pragma once
// A fixed-capacity FIFO of bytes (ring buffer): receive buffers of sessions and emulators, and the
// in-flight bytes of SimLink. Never allocates; push on a full queue is refused, not overwritten.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace cellctl::wire {

template <std::size_t Capacity>
class ByteQueue {
 public:
  // Appends as many bytes as fit; returns how many were taken.
  std::size_t push(std::span<const std::uint8_t> bytes) noexcept {
    std::size_t n = 0;
    while (n < bytes.size() && size_ < Capacity) {
      data_[(head_ + size_) % Capacity] = bytes[n++];
      ++size_;
    }
    return n;
  }
  // Copies up to out.size() bytes out of the front and removes them.
  std::size_t pop(std::span<std::uint8_t> out) noexcept {
    std::size_t n = 0;
    while (n < out.size() && size_ > 0) {
      out[n++] = data_[head_];
      drop(1);
    }
    return n;
  }
  [[nodiscard]] std::uint8_t operator[](std::size_t i) const noexcept {
    return data_[(head_ + i) % Capacity];
  }
  void drop(std::size_t n) noexcept {
    if (n > size_) n = size_;
    head_ = (head_ + n) % Capacity;
    size_ -= n;
  }
  void clear() noexcept { head_ = size_ = 0; }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  [[nodiscard]] std::size_t free_space() const noexcept { return Capacity - size_; }

 private:
  std::array<std::uint8_t, Capacity> data_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace cellctl::wire

#pragma once
// Bytes that each become readable at a time of their own, in order: the wire of a SimLink (a byte is
// due when its character time has passed) and the delay line of a FaultInjectingLink (a reply is due
// a set time after it arrived). Fixed capacity, no allocation; a byte is never overtaken by a later one.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "link/clock.hpp"

namespace cellctl::link {

template <std::size_t Capacity>
class TimedByteQueue {
 public:
  // False when full (the byte is lost, as in an overrun FIFO).
  bool push(std::uint8_t byte, TimePoint due) noexcept {
    if (size_ == Capacity) return false;
    slots_[(head_ + size_) % Capacity] = Slot{due, byte};
    ++size_;
    return true;
  }
  // Moves the bytes due by `now` (at most out.size()) to `out`; returns how many.
  std::size_t pop_due(std::span<std::uint8_t> out, TimePoint now) noexcept {
    std::size_t n = 0;
    while (n < out.size() && size_ > 0 && slots_[head_].due <= now) {
      out[n++] = slots_[head_].byte;
      head_ = (head_ + 1) % Capacity;
      --size_;
    }
    return n;
  }
  // When the oldest byte is due; nullopt when empty.
  [[nodiscard]] std::optional<TimePoint> next_due() const noexcept {
    if (size_ == 0) return std::nullopt;
    return slots_[head_].due;
  }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  [[nodiscard]] bool full() const noexcept { return size_ == Capacity; }
  void clear() noexcept { head_ = size_ = 0; }

 private:
  struct Slot {
    TimePoint due;
    std::uint8_t byte;
  };
  std::array<Slot, Capacity> slots_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace cellctl::link

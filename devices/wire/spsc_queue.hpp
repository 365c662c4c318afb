#pragma once
// Single-producer single-consumer ring of trivially copyable items: the control cycle pushes
// without locking or allocating, a writer thread pops (the journal, the telegram trace). Capacity is
// a power of two.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

namespace cellctl::wire {

// What a producer does when the consumer has fallen behind: in real time the cycle must not wait, so
// the item is counted as dropped; in virtual time nothing is real-time, so the cycle waits for room
// and nothing is ever dropped.
enum class WhenFull : std::uint8_t { drop_and_count, wait };

template <class T, std::size_t Capacity>
class SpscQueue {
  static_assert((Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "items are copied, never constructed in place");

 public:
  // Producer side. False when full (the item is not queued).
  bool push(const T& item) noexcept {
    const auto head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == Capacity) return false;
    items_[head & (Capacity - 1)] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side.
  std::optional<T> pop() noexcept {
    const auto tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return std::nullopt;
    T item = items_[tail & (Capacity - 1)];
    tail_.store(tail + 1, std::memory_order_release);
    return item;
  }

  [[nodiscard]] bool empty() const noexcept {
    return tail_.load(std::memory_order_acquire) == head_.load(std::memory_order_acquire);
  }

 private:
  std::array<T, Capacity> items_{};
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace cellctl::wire

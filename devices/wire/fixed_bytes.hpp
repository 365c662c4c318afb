#pragma once
// A byte string of bounded capacity that lives inline (no heap): telegrams are queued, kept for a
// retry and compared without allocating in the control cycle.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace cellctl::wire {

template <std::size_t Capacity>
class FixedBytes {
 public:
  FixedBytes() = default;
  explicit FixedBytes(std::span<const std::uint8_t> bytes) noexcept { assign(bytes); }

  // Copies at most Capacity bytes; returns false when the input had to be cut.
  bool assign(std::span<const std::uint8_t> bytes) noexcept {
    size_ = std::min(bytes.size(), Capacity);
    std::copy_n(bytes.begin(), size_, data_.begin());
    return size_ == bytes.size();
  }
  bool push_back(std::uint8_t b) noexcept {
    if (size_ == Capacity) return false;
    data_[size_++] = b;
    return true;
  }
  void clear() noexcept { size_ = 0; }

  [[nodiscard]] std::span<const std::uint8_t> view() const noexcept { return {data_.data(), size_}; }
  [[nodiscard]] std::span<std::uint8_t> storage() noexcept { return data_; }
  void resize(std::size_t n) noexcept { size_ = std::min(n, Capacity); }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  [[nodiscard]] std::uint8_t operator[](std::size_t i) const noexcept { return data_[i]; }

  friend bool operator==(const FixedBytes& a, const FixedBytes& b) noexcept {
    return std::ranges::equal(a.view(), b.view());
  }

 private:
  std::array<std::uint8_t, Capacity> data_{};
  std::size_t size_ = 0;
};

}  // namespace cellctl::wire

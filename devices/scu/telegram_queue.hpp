#pragma once
// A bounded FIFO of queued telegrams that never allocates, with the two operations a session needs
// beyond push/pop: put something at the front (a retry that must not lose its turn) and remove
// entries that became pointless (a queued move preempted by a stop).

#include <array>
#include <cstddef>
#include <utility>

namespace cellctl::scu {

template <class T, std::size_t N>
class TelegramQueue {
 public:
  [[nodiscard]] bool push_back(const T& v) noexcept {
    if (size_ == N) return false;
    items_[size_++] = v;
    return true;
  }
  [[nodiscard]] bool push_front(const T& v) noexcept {
    if (size_ == N) return false;
    for (std::size_t i = size_; i > 0; --i) items_[i] = std::move(items_[i - 1]);
    items_[0] = v;
    ++size_;
    return true;
  }
  [[nodiscard]] const T& front() const noexcept { return items_[0]; }
  void pop_front() noexcept { remove_at(0); }
  template <class Pred>
  std::size_t remove_if(Pred&& pred) noexcept {
    std::size_t removed = 0;
    for (std::size_t i = 0; i < size_;) {
      if (pred(items_[i])) {
        remove_at(i);
        ++removed;
      } else {
        ++i;
      }
    }
    return removed;
  }
  // The first queued item `pred` holds for (nullptr: none), to change in place.
  template <class Pred>
  [[nodiscard]] T* find_if(Pred&& pred) noexcept {
    for (std::size_t i = 0; i < size_; ++i)
      if (pred(items_[i])) return &items_[i];
    return nullptr;
  }
  template <class Pred>
  [[nodiscard]] bool any(Pred&& pred) const noexcept {
    for (std::size_t i = 0; i < size_; ++i)
      if (pred(items_[i])) return true;
    return false;
  }
  void clear() noexcept { size_ = 0; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] std::size_t free_space() const noexcept { return N - size_; }

 private:
  void remove_at(std::size_t i) noexcept {
    for (; i + 1 < size_; ++i) items_[i] = std::move(items_[i + 1]);
    --size_;
  }
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

}  // namespace cellctl::scu

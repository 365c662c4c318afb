#include "link/sim_link.hpp"

#include <algorithm>

namespace cellctl::link {

SimLink::SimLink(const Clock& clock, LineFormat format, std::string name)
    : clock_(clock),
      format_(format),
      master_end_(*this, to_device_, to_master_, name + ":master"),
      device_end_(*this, to_master_, to_device_, name + ":device") {}

std::optional<TimePoint> SimLink::next_delivery() const noexcept {
  const auto a = to_device_.next_delivery();
  const auto b = to_master_.next_delivery();
  if (a && b) return std::min(*a, *b);
  return a ? a : b;
}

std::size_t SimLink::Wire::send(std::span<const std::uint8_t> bytes, TimePoint now,
                                Duration char_time) noexcept {
  std::size_t n = 0;
  TimePoint t = std::max(now, line_free_at_);
  while (n < bytes.size() && size_ < kCapacity) {
    t += char_time;
    slots_[(head_ + size_) % kCapacity] = Slot{t, bytes[n++]};
    ++size_;
  }
  line_free_at_ = t;
  return n;
}

std::size_t SimLink::Wire::receive(std::span<std::uint8_t> out, TimePoint now) noexcept {
  std::size_t n = 0;
  while (n < out.size() && size_ > 0 && slots_[head_].at <= now) {
    out[n++] = slots_[head_].byte;
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  return n;
}

std::optional<TimePoint> SimLink::Wire::next_delivery() const noexcept {
  if (size_ == 0) return std::nullopt;
  return slots_[head_].at;
}

IoResult SimLink::End::read(std::span<std::uint8_t> buffer) {
  return {in_.receive(buffer, owner_.clock_.now())};
}

IoResult SimLink::End::write(std::span<const std::uint8_t> bytes) {
  if (owner_.cut_) return {bytes.size()};  // written into a cable that leads nowhere
  return {out_.send(bytes, owner_.clock_.now(), owner_.format_.char_time())};
}

}  // namespace cellctl::link

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
  while (n < bytes.size() && !bytes_.full()) {
    t += char_time;
    (void)bytes_.push(bytes[n++], t);  // room: the loop checks it
  }
  line_free_at_ = t;
  return n;
}

IoResult SimLink::End::read(std::span<std::uint8_t> buffer) {
  return {in_.receive(buffer, owner_.clock_.now())};
}

IoResult SimLink::End::write(std::span<const std::uint8_t> bytes) {
  if (owner_.cut_) return {bytes.size()};  // written into a cable that leads nowhere
  return {out_.send(bytes, owner_.clock_.now(), owner_.format_.char_time())};
}

}  // namespace cellctl::link

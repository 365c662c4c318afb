// scu::Emulator: remote mode and its watchdog — RO opens it with a Safety_ID, RC keeps it alive (and
// exchanges a cyclic object's data), RA closes it; an RC missing for 500 ms stops motion and sets
// error bit 22. What a request may do while remote mode is (not) open is decided here.
#include <algorithm>

#include "scu/data_list.hpp"
#include "scu/emulator.hpp"

namespace cellctl::scu {

void Emulator::run_watchdog(link::TimePoint now) {
  if (!remote_open_ || lapsed_ || now - last_rc_at_ <= kWatchdogPeriod) return;
  lapsed_ = true;
  raise_error(error_bit::kRemoteTimeout);
  // Safety_ID 0 and 1 terminate all movements, 2 only the remote ones; every motion of the emulator
  // is a remote one, so all three stop everything.
  stop_all(false);
}

Status Emulator::remote_permission() const noexcept {
  if (!remote_open_ || !rc_seen_) return Status::permission_error;  // RO, then RC before anything else
  if (lapsed_ && safety_id_ == 0) return Status::permission_error;  // after a lapse only RC, RA, RO
  return Status::ack;
}

Status Emulator::handle(const OpenRequest& r, link::TimePoint now) {
  if (r.safety_id > 2) return Status::parameter_data_error;
  remote_open_ = true;
  rc_seen_ = false;
  lapsed_ = false;
  safety_id_ = r.safety_id;
  last_rc_at_ = now;  // the watchdog runs from RO: the first RC is due within 500 ms as well
  error_codes_[0] &= ~ErrorWord::mask(error_bit::kRemoteTimeout);
  return Status::ack;
}

Status Emulator::handle(const AbortRequest&, link::TimePoint) {
  if (remote_open_) stop_all(true);  // back to normal mode: nothing remote keeps moving
  remote_open_ = false;
  rc_seen_ = false;
  running_.fill(false);
  return Status::ack;
}

Status Emulator::handle(const CyclicRequest& r, link::TimePoint now, wire::ByteWriter& out) {
  if (!remote_open_) return Status::permission_error;
  if (r.index != kNoCyclicObject && r.index >= kCyclicObjectCount) return Status::parameter_data_error;
  if (r.index == kNoCyclicObject && !r.write_data.empty()) return Status::parameter_count_error;
  if (rc_seen_) max_rc_gap_ = std::max(max_rc_gap_, now - last_rc_at_);
  rc_seen_ = true;
  last_rc_at_ = now;
  ++rc_count_;
  if (lapsed_ && safety_id_ != 0) lapsed_ = false;  // Safety_ID 1/2: RC resumes remote mode
  if (r.index == kNoCyclicObject) return Status::ack;

  const auto& obj = cyclic_objects_[r.index];
  // Write data: the concatenated values of the first six IDs, checked whole before anything changes.
  std::size_t expected = 0;
  for (std::size_t i = 0; i < 6; ++i)
    if (obj[i] != kUnusedDataId) expected += value_size(obj[i]);
  if (r.write_data.size() != expected) return Status::parameter_count_error;
  std::size_t at = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    if (obj[i] == kUnusedDataId) continue;
    const auto n = value_size(obj[i]);
    if (const auto s = check_write(obj[i], r.write_data.subspan(at, n)); s != Status::ack) return s;
    at += n;
  }
  at = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    if (obj[i] == kUnusedDataId) continue;
    const auto n = value_size(obj[i]);
    apply_write(obj[i], r.write_data.subspan(at, n));
    at += n;
  }
  for (std::size_t i = 6; i < 12; ++i)
    if (obj[i] != kUnusedDataId && !read_value(obj[i], out)) return Status::parameter_data_error;
  return out.ok() ? Status::ack : Status::parameter_data_error;
}

}  // namespace cellctl::scu

#include "device_seam/cell_device.hpp"

#include <fmt/format.h>

#include "link/fault_reason.hpp"

namespace cellctl::device_seam {

CellDevice::CellDevice(std::size_t slot, std::string_view name, std::string_view title, Reopen reopen)
    : slot_(slot), name_(name), title_(title), reopen_(std::move(reopen)) {
  lost_reason_.reserve(link::kFaultReasonCapacity);
}

void CellDevice::notes(std::vector<std::string>& out) const {
  if (session().lifecycle() == link::Lifecycle::fault)
    out.push_back(fmt::format("{}: {}", title_, session().fault_reason()));
}

void CellDevice::observe(link::TimePoint now, const cell::CellState&) noexcept {
  note_loss(now);
}

void CellDevice::note_loss(link::TimePoint now) noexcept {
  const auto& s = session();
  if (lost_at_ || s.lifecycle() != link::Lifecycle::fault) return;
  // Since the last good reply: a silent line faults the session only after link_fault_after.
  lost_at_ = now - s.silent_for(now);
  lost_reason_.assign(s.fault_reason());  // within the capacity reserved: no allocation
}

void CellDevice::resolve(Safe safe, link::TimePoint now) noexcept {
  if (resolved_) return;
  resolved_ = safe;
  resolved_at_ = now;
}

void CellDevice::recover(link::TimePoint now) {
  if (now < next_retry_) return;
  next_retry_ = now + kRetry;
  if (!reopen_ || !reopen_()) {
    ++reopen_failures_;
    return;
  }
  ++recoveries_;
  session().activate(now);
}

std::string CellDevice::loss_evidence(std::string_view who, const StopContext& ctx) const {
  std::string out;
  if (lost_at_) out = fmt::format("{} lost at {:.3f} s ({}); ", who, ctx.t_of(*lost_at_), lost_reason_);
  if (recoveries_ > 0 || reopen_failures_ > 0)
    out +=
        fmt::format("port opened again {} time(s), {} attempt(s) refused; ", recoveries_, reopen_failures_);
  return out;
}

}  // namespace cellctl::device_seam

#include "runtime/safe_stop.hpp"

#include <algorithm>

namespace cellctl::runtime {

SafeStop::SafeStop(CellDevices& devices, link::Duration confirm_within, link::TimePoint start)
    : devices_(devices),
      context_{.start = start, .begun_at = std::nullopt, .confirm_within = confirm_within} {}

void SafeStop::observe(link::TimePoint now, const cell::CellState& state) noexcept {
  for (auto* d : devices_.devices()) d->observe(now, state);
}

void SafeStop::begin(link::TimePoint now) {
  context_.begun_at = now;
  for (auto* d : devices_.devices()) d->begin_stop(now);
}

void SafeStop::step(link::TimePoint now, bool stopping) {
  const auto devices = devices_.devices();
  if (!context_.begun_at) {
    // Before the end, only a lost device that moves something, and only when the run is being stopped.
    if (!stopping) return;
    for (auto* d : devices)
      if (d->moves() && d->lost_at()) d->step_stop(now, context_);
    return;
  }
  // Devices that drive the axes first: one resolved in this step frees the watchers in the same step.
  for (auto* d : devices)
    if (d->drives_axes()) d->step_stop(now, context_);
  context_.axes_resolved = std::all_of(devices.begin(), devices.end(),
                                       [](const auto* d) { return !d->drives_axes() || d->resolved(); });
  for (auto* d : devices)
    if (!d->drives_axes()) d->step_stop(now, context_);
}

bool SafeStop::done() const noexcept {
  const auto devices = devices_.devices();
  return std::all_of(devices.begin(), devices.end(), [](const auto* d) { return d->resolved().has_value(); });
}

const device_seam::CellDevice* SafeStop::at(std::size_t slot) const noexcept {
  for (const auto* d : devices_.devices())
    if (d->slot() == slot) return d;
  return nullptr;
}

std::string SafeStop::lost_reason(std::size_t slot) const {
  const auto* d = at(slot);
  return d ? d->lost_reason() : std::string();
}

Verdicts SafeStop::verdicts() const {
  Verdicts out;
  for (const auto* d : devices_.devices())
    out[d->slot()] = DeviceSafety{d->name(), d->resolved().value_or(Safe::unknown), d->evidence(context_)};
  return out;
}

}  // namespace cellctl::runtime

#include "runtime/safe_stop.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "link/fault_reason.hpp"

namespace cellctl::runtime {
namespace {

// Every fitted actuator's last refresh showed no motion.
bool all_at_rest(const scu::Session& s) noexcept {
  const auto& snap = s.snapshot();
  if (!snap.last_refresh) return false;
  for (const auto& a : snap.actuators)
    if (a.configured && a.status.motion_active) return false;
  return true;
}

}  // namespace

SafeStop::SafeStop(const config::CellConfig& cell, CellDevices& devices, CellLinks& links,
                   link::Duration confirm_within, link::TimePoint start)
    : cell_(cell), devices_(devices), links_(links), confirm_within_(confirm_within), start_(start) {
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    track_[d].present = devices_.sessions()[d] != nullptr;
    track_[d].lost_reason.reserve(link::kFaultReasonCapacity);
  }
}

void SafeStop::note_loss(Track& t, const link::DeviceSession& s, link::TimePoint now) {
  if (t.lost_at || s.lifecycle() != link::Lifecycle::fault) return;
  // Since the last good reply: a silent line faults the session only after link_fault_after.
  t.lost_at = now - s.silent_for(now);
  t.lost_reason.assign(s.fault_reason());  // within the capacity reserved: no allocation
}

void SafeStop::observe(link::TimePoint now) noexcept {
  if (auto* s = devices_.scu()) {
    note_loss(track_[slot(cell::Device::scu)], *s, now);
    const auto& snap = s->snapshot();
    if (snap.last_refresh && snap.last_refresh != scu_.last_refresh) {
      scu_.last_refresh = snap.last_refresh;
      for (std::size_t i = 0; i < cell_.axes.size() && i < cell::kMaxAxes; ++i)
        scu_.last_mm[i] = snap.actuators[static_cast<std::size_t>(cell_.axes[i].actuator - 1)].position_mm;
    }
  }
  if (auto* s = devices_.spindle()) {
    note_loss(track_[slot(cell::Device::spindle)], *s, now);
    const auto& snap = s->snapshot();
    if (snap.run_requested) {
      spindle_.last_set_hz = snap.requested_frequency_hz;
      spindle_.run_sent = true;
    }
    if (snap.status_valid && snap.status_age == link::Duration::zero()) {
      spindle_.last_status = now;
      spindle_.last_at_rest = snap.at_rest;
      if (snap.at_rest && !snap.run_requested) spindle_.run_sent = false;
    }
  }
  if (auto* s = devices_.encoder()) {
    note_loss(track_[slot(cell::Device::encoder)], *s, now);
    const auto& snap = s->snapshot();
    if (snap.data_exchange && s->lifecycle() == link::Lifecycle::active) {
      encoder_.last_seen = now;
      encoder_.mm = snap.position_mm;
      encoder_.mm_s = snap.velocity_mm_s;
    }
  }
}

void SafeStop::begin(link::TimePoint now) {
  begun_at_ = now;
  // Axes stopped and remote mode closed (RS, RA); the spindle stopped until it stands still.
  if (auto* s = devices_.scu()) s->deactivate(now);
  if (auto* s = devices_.spindle()) s->deactivate(now);
}

void SafeStop::resolve(Track& t, Safe safe, link::TimePoint now) noexcept {
  if (t.resolved) return;
  t.resolved = safe;
  t.resolved_at = now;
}

void SafeStop::recover(cell::Device d, link::DeviceSession& s, link::TimePoint now) {
  auto& t = track_[slot(d)];
  if (now < t.next_retry) return;
  t.next_retry = now + kRetry;
  if (!links_.reopen(d).ok()) {
    ++t.reopen_failures;
    return;
  }
  ++t.recoveries;
  s.activate(now);
}

void SafeStop::step(link::TimePoint now, bool stopping) {
  if (!begun_at_) {
    // Before the end, only a lost SCU or spindle, and only when the run is being stopped.
    if (!stopping) return;
    if (track_[slot(cell::Device::scu)].lost_at) step_scu(now);
    if (track_[slot(cell::Device::spindle)].lost_at) step_spindle(now);
    return;
  }
  step_scu(now);
  step_spindle(now);
  step_encoder(now);
}

void SafeStop::step_scu(link::TimePoint now) {
  auto* s = devices_.scu();
  auto& t = track_[slot(cell::Device::scu)];
  if (!s || t.resolved) return;
  const auto& snap = s->snapshot();
  if (t.lost_at) {
    scu_.bound_at =
        std::max(scu_.bound_at, s->last_sent() + kScuCommunicationTimeout + s->config().stopping_time);
    if (!scu_.give_up) scu_.give_up = scu_.bound_at;  // no new attempt after the first bound
  }
  switch (s->lifecycle()) {
    case link::Lifecycle::fault:
      if (now >= scu_.bound_at) return resolve(t, Safe::bounded, now);
      if (now < *scu_.give_up) recover(cell::Device::scu, *s, now);
      return;
    case link::Lifecycle::activating:
      if (t.lost_at && now >= scu_.bound_at) resolve(t, Safe::bounded, now);
      return;
    case link::Lifecycle::active:
      // Back after a loss: F20 stops every actuator, and a refresh after it shows them at rest.
      if (!scu_.f20_asked) scu_.f20_asked = s->emergency_stop();
      if (snap.emergency_stop_open && !scu_.refreshes_at_f20) scu_.refreshes_at_f20 = snap.refreshes;
      if (scu_.refreshes_at_f20 && snap.refreshes > *scu_.refreshes_at_f20 && all_at_rest(*s)) {
        scu_.rest_seen_at = now;
        s->deactivate(now);
      } else if (t.lost_at && now >= scu_.bound_at) {
        resolve(t, Safe::bounded, now);
      }
      return;
    case link::Lifecycle::deactivating:
      if (all_at_rest(*s) && (!t.lost_at || scu_.refreshes_at_f20)) scu_.rest_seen_at = now;
      if (begun_at_ && now >= *begun_at_ + confirm_within_ && !t.lost_at)
        resolve(t, scu_.rest_seen_at ? Safe::observed : Safe::unknown, now);
      return;
    case link::Lifecycle::inactive:
      if (!scu_.closed_at) {
        scu_.closed_at = now;
        scu_.moving_at_close = !all_at_rest(*s);
      }
      if (!scu_.moving_at_close || scu_.rest_seen_at) return resolve(t, Safe::observed, now);
      // RA ends every remote motion: at rest within the stopping time, unseen.
      if (now >= *scu_.closed_at + s->config().stopping_time) resolve(t, Safe::bounded, now);
      return;
  }
}

void SafeStop::step_spindle(link::TimePoint now) {
  auto* s = devices_.spindle();
  auto& t = track_[slot(cell::Device::spindle)];
  if (!s || t.resolved) return;
  const bool out_of_time = now >= begun_at_.value_or(t.lost_at.value_or(now)) + confirm_within_;
  // Unconfirmed: at rest as last seen and never started since is bounded; else it may still turn.
  const Safe unconfirmed = spindle_.run_sent || !spindle_.last_at_rest ? Safe::unknown : Safe::bounded;
  switch (s->lifecycle()) {
    case link::Lifecycle::fault:
      if (out_of_time) return resolve(t, unconfirmed, now);
      recover(cell::Device::spindle, *s, now);
      return;
    case link::Lifecycle::activating:
    case link::Lifecycle::deactivating:
      if (out_of_time) resolve(t, unconfirmed, now);
      return;
    case link::Lifecycle::active:
      s->deactivate(now);  // back after a loss: CMD System Stopp until STILLSTAND
      return;
    case link::Lifecycle::inactive:
      // Only a statusout after the stop's ACK reporting STILLSTAND closes the session.
      spindle_.standstill_at = now;
      resolve(t, Safe::observed, now);
      return;
  }
}

void SafeStop::step_encoder(link::TimePoint now) {
  auto* s = devices_.encoder();
  auto& t = track_[slot(cell::Device::encoder)];
  if (!s || t.resolved) return;
  const auto& scu = track_[slot(cell::Device::scu)];
  if (t.lost_at || s->lifecycle() == link::Lifecycle::fault) return resolve(t, Safe::bounded, now);
  // Observed only when the positions kept coming through the stop: a master that left data exchange
  // (and may be starting it again), or whose replies stopped being good, saw nothing of the axes.
  if (!s->snapshot().data_exchange || s->lifecycle() != link::Lifecycle::active ||
      s->silent_for(now) > kRetry)
    encoder_.missed = true;
  if (scu.present && !scu.resolved) return;  // watching the axes until the SCU is resolved
  if (s->lifecycle() == link::Lifecycle::active || s->lifecycle() == link::Lifecycle::activating)
    s->deactivate(now);
  resolve(t, encoder_.missed ? Safe::bounded : Safe::observed, now);
}

bool SafeStop::done() const noexcept {
  return std::all_of(track_.begin(), track_.end(), [](const Track& t) { return !t.present || t.resolved; });
}

std::string SafeStop::scu_evidence() const {
  const auto& t = track_[slot(cell::Device::scu)];
  std::string positions;
  for (std::size_t i = 0; i < cell_.axes.size() && i < cell::kMaxAxes; ++i)
    positions +=
        fmt::format("{}{} {:.2f} mm", positions.empty() ? "" : ", ", cell_.axes[i].name, scu_.last_mm[i]);
  std::string out;
  if (t.lost_at) out = fmt::format("SCU lost at {:.3f} s ({}); ", t_of(*t.lost_at), t.lost_reason);
  if (t.recoveries > 0 || t.reopen_failures > 0)
    out +=
        fmt::format("port opened again {} time(s), {} attempt(s) refused; ", t.recoveries, t.reopen_failures);
  switch (t.resolved.value_or(Safe::unknown)) {
    case Safe::observed:
      out += t.lost_at
                 ? fmt::format("F20 sent after it came back; every actuator reported at rest at {:.3f} s",
                               t_of(scu_.rest_seen_at.value_or(t.resolved_at)))
                 : fmt::format("every actuator reported at rest, remote mode closed at {:.3f} s",
                               t_of(scu_.closed_at.value_or(t.resolved_at)));
      break;
    case Safe::bounded:
      out += scu_.closed_at
                 ? fmt::format(
                       "remote mode closed at {:.3f} s while an actuator still moved; at rest by {:.3f} s "
                       "(stopping time)",
                       t_of(*scu_.closed_at), t_of(t.resolved_at))
                 : fmt::format(
                       "stop not confirmed; the SCU's communication time-out ({:.1f} s after the last "
                       "request) and "
                       "the actuators' stopping time had passed at {:.3f} s: its own protection stopped them",
                       link::to_seconds(kScuCommunicationTimeout), t_of(scu_.bound_at));
      break;
    case Safe::unknown:
      out += "actuators still reported moving when the safe-stop ended";
      break;
  }
  out += "; last SCU positions";
  out += scu_.last_refresh ? fmt::format(" ({:.3f} s): {}", t_of(*scu_.last_refresh), positions) : ": none";
  for (const auto& a : cell_.axes)
    if (a.encoder && encoder_.last_seen)
      out += fmt::format("; last measured {} {:.2f} mm at {:.3f} s ({:.2f} mm/s)", a.name, encoder_.mm,
                         t_of(*encoder_.last_seen), encoder_.mm_s);
  return out;
}

std::string SafeStop::spindle_evidence() const {
  const auto& t = track_[slot(cell::Device::spindle)];
  std::string out;
  if (t.lost_at) out = fmt::format("converter lost at {:.3f} s ({}); ", t_of(*t.lost_at), t.lost_reason);
  if (t.recoveries > 0 || t.reopen_failures > 0)
    out +=
        fmt::format("port opened again {} time(s), {} attempt(s) refused; ", t.recoveries, t.reopen_failures);
  const std::string last =
      spindle_.last_status ? fmt::format("{:.3f} s", t_of(*spindle_.last_status)) : "never";
  switch (t.resolved.value_or(Safe::unknown)) {
    case Safe::observed:
      out += fmt::format("CMD System Stopp acknowledged and STILLSTAND reported at {:.3f} s",
                         t_of(t.resolved_at));
      break;
    case Safe::bounded:
      out += fmt::format(
          "stop unconfirmed, but the converter reported STILLSTAND last (at {}) and no start was "
          "sent since",
          last);
      break;
    case Safe::unknown:
      out += fmt::format(
          "CMD System Stopp unconfirmed after {:.1f} s of trying (last status {}): the spindle may still be "
          "turning "
          "at {:.0f} Hz, the last set frequency",
          link::to_seconds(confirm_within_), last, spindle_.last_set_hz);
      break;
  }
  return out;
}

std::string SafeStop::encoder_evidence() const {
  const auto& t = track_[slot(cell::Device::encoder)];
  std::string axis = "the axis";
  for (const auto& a : cell_.axes)
    if (a.encoder) axis = a.name;
  if (t.resolved == Safe::observed)
    return encoder_.last_seen ? fmt::format(
                                    "moves nothing of its own; positions watched to the end: {} {:.2f} mm at "
                                    "{:.3f} s",
                                    axis, encoder_.mm, t_of(*encoder_.last_seen))
                              : std::string("moves nothing of its own; closed in order");
  std::string why = t.lost_reason;
  if (const auto* s = devices_.encoder(); why.empty() && s && !s->restart_reason().empty())
    why = "left data exchange: " + s->restart_reason();
  return fmt::format("moves nothing of its own; positions unwatched since {} ({})",
                     encoder_.last_seen ? fmt::format("{:.3f} s", t_of(*encoder_.last_seen)) : "the start",
                     why.empty() ? "left data exchange" : why);
}

std::array<std::optional<DeviceSafety>, cell::kDevices> SafeStop::verdicts() const {
  std::array<std::optional<DeviceSafety>, cell::kDevices> out;
  const auto verdict = [&](cell::Device d, std::string evidence) {
    const auto& t = track_[slot(d)];
    if (t.present) out[slot(d)] = DeviceSafety{t.resolved.value_or(Safe::unknown), std::move(evidence)};
  };
  verdict(cell::Device::scu, scu_evidence());
  verdict(cell::Device::spindle, spindle_evidence());
  verdict(cell::Device::encoder, encoder_evidence());
  return out;
}

}  // namespace cellctl::runtime

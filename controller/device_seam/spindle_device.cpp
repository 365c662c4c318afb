#include "device_seam/spindle_device.hpp"

#include <fmt/format.h>

namespace cellctl::device_seam {

SpindleDevice::SpindleDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                             Reopen reopen)
    : CellDevice(slot, "spindle", "spindle", std::move(reopen)), session_(link, cell.spindle->session) {}

void SpindleDevice::read(link::TimePoint, cell::CellState& out) {
  const auto& s = session_.snapshot();
  auto& sp = out.spindle;
  sp.active = session_.lifecycle() == link::Lifecycle::active;
  const double sign = s.direction == spindle::Direction::clockwise ? 1.0 : -1.0;
  sp.set_hz = s.requested_frequency_hz;
  // STILLSTAND comes with every fast status poll, the frequency only with the slower value poll.
  sp.at_rest = !s.status_valid || s.at_rest;
  sp.actual_hz = sp.at_rest ? 0.0 : sign * s.actual_frequency_hz;
  sp.running = s.run_requested;
  sp.at_speed = s.status_valid && s.at_speed;
  sp.settled = sp.at_speed && s.settled;
  sp.warning = s.warning();
  sp.fault = s.fault();
  sp.fault_number = s.fault() ? s.error_number : 0;
  sp.over_temperature = s.motor_over_temperature;
  sp.current_limit = s.current_limit;
  sp.start_refused = s.start_refused;
  sp.error_number = s.error_number;
}

void SpindleDevice::apply(const cell::Intents& in) {
  if (session_.lifecycle() != link::Lifecycle::active) return;
  // Refused only with the command queue full, which one cycle's intents never fill (a start queues
  // three); the operator's next reset asks again.
  if (in.spindle.reset) (void)session_.reset();
  const auto& s = session_.snapshot();
  // A controlled hold (category 2) keeps the spindle running; stops take `run` away themselves.
  const bool run = in.spindle.run && in.halt != cell::Halt::immediate;
  const auto dir =
      in.spindle.clockwise ? spindle::Direction::clockwise : spindle::Direction::counter_clockwise;
  const bool reversing = dir != s.direction;
  if (!run || (s.run_requested && reversing)) {
    if (s.run_requested) (void)session_.stop();  // taken: the session is active and a stop empties the queue
    return;
  }
  if (!s.run_requested) {
    // After a change of direction the motor runs down to rest before it starts the other way.
    if (reversing && !s.at_rest) return;
    // Refused with the queue full, or for a frequency beyond 0 … 65535 Hz (a recipe's is inside the
    // cell's spindle limits): run_requested stays false and the start is asked for again next cycle.
    (void)session_.start(in.spindle.frequency_hz, dir);
  } else if (in.spindle.frequency_hz != s.requested_frequency_hz) {
    // As the start: refused, the frequency asked for is unchanged and asked again next cycle.
    (void)session_.set_frequency(in.spindle.frequency_hz);
  }
}

void SpindleDevice::notes(std::vector<std::string>& out) const {
  CellDevice::notes(out);
  if (session_.snapshot().start_refused)
    out.push_back("spindle: " + session_.snapshot().start_refused_reason);
}

// --- the safe-stop ---

void SpindleDevice::observe(link::TimePoint now, const cell::CellState&) noexcept {
  note_loss(now);
  const auto& snap = session_.snapshot();
  if (snap.run_requested) {
    stop_.last_set_hz = snap.requested_frequency_hz;
    stop_.run_sent = true;
  }
  if (snap.status_valid && snap.status_age == link::Duration::zero()) {
    stop_.last_status = now;
    stop_.last_at_rest = snap.at_rest;
    if (snap.at_rest && !snap.run_requested) stop_.run_sent = false;
  }
}

void SpindleDevice::begin_stop(link::TimePoint now) {
  session_.deactivate(now);
}

void SpindleDevice::step_stop(link::TimePoint now, const StopContext& ctx) {
  if (resolved()) return;
  const bool out_of_time = now >= ctx.begun_at.value_or(lost_at().value_or(now)) + ctx.confirm_within;
  // Unconfirmed: at rest as last seen and never started since is bounded; else it may still turn.
  const Safe unconfirmed = stop_.run_sent || !stop_.last_at_rest ? Safe::unknown : Safe::bounded;
  switch (session_.lifecycle()) {
    case link::Lifecycle::fault:
      if (out_of_time) return resolve(unconfirmed, now);
      recover(now);
      return;
    case link::Lifecycle::activating:
    case link::Lifecycle::deactivating:
      if (out_of_time) resolve(unconfirmed, now);
      return;
    case link::Lifecycle::active:
      session_.deactivate(now);  // back after a loss: CMD System Stopp until STILLSTAND
      return;
    case link::Lifecycle::inactive:
      // Only a statusout after the stop's ACK reporting STILLSTAND closes the session.
      resolve(Safe::observed, now);
      return;
  }
}

std::string SpindleDevice::evidence(const StopContext& ctx) const {
  std::string out = loss_evidence("converter", ctx);
  const std::string last =
      stop_.last_status ? fmt::format("{:.3f} s", ctx.t_of(*stop_.last_status)) : "never";
  switch (resolved().value_or(Safe::unknown)) {
    case Safe::observed:
      out += fmt::format("CMD System Stopp acknowledged and STILLSTAND reported at {:.3f} s",
                         ctx.t_of(resolved_at()));
      break;
    case Safe::bounded:
      out += fmt::format(
          "stop unconfirmed, but the converter reported STILLSTAND last (at {}) and no start was sent since",
          last);
      break;
    case Safe::unknown:
      out += fmt::format(
          "CMD System Stopp unconfirmed after {:.1f} s of trying (last status {}): the spindle may still be "
          "turning at {:.0f} Hz, the last set frequency",
          link::to_seconds(ctx.confirm_within), last, stop_.last_set_hz);
      break;
  }
  return out;
}

}  // namespace cellctl::device_seam

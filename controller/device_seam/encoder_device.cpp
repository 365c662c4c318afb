#include "device_seam/encoder_device.hpp"

#include <fmt/format.h>

#include <cmath>

namespace cellctl::device_seam {

EncoderDevice::EncoderDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                             Reopen reopen)
    : CellDevice(slot, "encoder", "encoder", std::move(reopen)),
      cell_(cell),
      session_(link, cell.encoder->session) {}

void EncoderDevice::read(link::TimePoint, cell::CellState& out) {
  const auto& e = session_.snapshot();
  auto& enc = out.encoder;
  enc.data_exchange = e.data_exchange;
  // input_valid covers the Ready bit and inputs the manual does not allow (never a stale position).
  enc.ready = e.data_exchange && e.input_valid;
  enc.alarm = e.diagnosis && e.diagnosis->alarms != 0;
  enc.limit_switch = e.has_status_bits && e.status.limit_switch;
  enc.diagnosis_pending = e.new_diagnosis;
  enc.mm = e.position_mm;
  enc.mm_s = e.velocity_mm_s;
  enc.preset_id = preset_.id;
  enc.preset_done = preset_.done;
  enc.preset_failed = preset_.failed;
  enc.preset_failure = preset_.failure;
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    auto& st = out.axes[i];
    st.measured = cell_.axes[i].encoder;
    if (!st.measured) continue;
    st.encoder_mm = enc.mm;
    st.encoder_mm_s = enc.mm_s;
  }
}

void EncoderDevice::follow_preset() {
  // The outcome of the preset in flight: the handshake ends (done or failed) a few exchanges later.
  if (!preset_.sent || preset_.done || preset_.failed) return;
  const auto& cmd = session_.snapshot().command;
  if (cmd.kind != encoder::Handshake::Kind::preset) return;
  if (cmd.phase == encoder::Handshake::Phase::done) {
    preset_.done = true;
    session_.clear_command();
  } else if (cmd.phase == encoder::Handshake::Phase::failed) {
    preset_.failed = true;
    preset_.failure = cmd.failure;
    session_.clear_command();
  }
}

void EncoderDevice::apply(const cell::Intents& in) {
  follow_preset();
  if (in.encoder.preset_id == 0 || in.encoder.preset_id == preset_.id) return;
  preset_ = Preset{};
  preset_.id = in.encoder.preset_id;
  const double counts = in.encoder.preset_mm * session_.counts_per_mm();
  if (session_.lifecycle() != link::Lifecycle::active || counts < 0.0 ||
      !session_.preset(static_cast<std::uint32_t>(std::lround(counts)))) {
    preset_.failed = true;
    preset_.failure =
        "the encoder session refused the preset (not in data exchange, a command running, or the value "
        "beyond the measuring range)";
    return;
  }
  preset_.sent = true;
}

void EncoderDevice::notes(std::vector<std::string>& out) const {
  CellDevice::notes(out);
  if (!session_.restart_reason().empty())
    out.push_back("encoder: DP start-up begun again: " + session_.restart_reason());
}

// --- the safe-stop ---

void EncoderDevice::observe(link::TimePoint now, const cell::CellState&) noexcept {
  note_loss(now);
  const auto& snap = session_.snapshot();
  if (snap.data_exchange && session_.lifecycle() == link::Lifecycle::active) {
    stop_.last_seen = now;
    stop_.mm = snap.position_mm;
  }
}

void EncoderDevice::step_stop(link::TimePoint now, const StopContext& ctx) {
  if (resolved()) return;
  if (lost_at() || session_.lifecycle() == link::Lifecycle::fault) return resolve(Safe::bounded, now);
  // Observed only when the positions kept coming through the stop: a master that left data exchange
  // (and may be starting it again), or whose replies stopped being good, saw nothing of the axes.
  if (!session_.snapshot().data_exchange || session_.lifecycle() != link::Lifecycle::active ||
      session_.silent_for(now) > kRetry)
    stop_.missed = true;
  if (!ctx.axes_resolved) return;  // watching the axes until whatever drives them is resolved
  if (session_.lifecycle() == link::Lifecycle::active || session_.lifecycle() == link::Lifecycle::activating)
    session_.deactivate(now);
  resolve(stop_.missed ? Safe::bounded : Safe::observed, now);
}

std::string EncoderDevice::evidence(const StopContext& ctx) const {
  std::string axis = "the axis";
  for (const auto& a : cell_.axes)
    if (a.encoder) axis = a.name;
  if (resolved() == Safe::observed)
    return stop_.last_seen ? fmt::format(
                                 "moves nothing of its own; positions watched to the end: {} {:.2f} mm at "
                                 "{:.3f} s",
                                 axis, stop_.mm, ctx.t_of(*stop_.last_seen))
                           : std::string("moves nothing of its own; closed in order");
  std::string why = lost_reason();
  if (why.empty() && !session_.restart_reason().empty())
    why = "left data exchange: " + session_.restart_reason();
  return fmt::format("moves nothing of its own; positions unwatched since {} ({})",
                     stop_.last_seen ? fmt::format("{:.3f} s", ctx.t_of(*stop_.last_seen)) : "the start",
                     why.empty() ? "left data exchange" : why);
}

}  // namespace cellctl::device_seam

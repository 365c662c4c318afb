#include "runtime/cell_devices.hpp"

#include <cmath>

namespace cellctl::runtime {
namespace {

cell::LinkState link_state(const link::DeviceSession& s, link::TimePoint now) {
  const auto& h = s.health();
  return {.active = s.lifecycle() == link::Lifecycle::active,
          .fault = s.lifecycle() == link::Lifecycle::fault,
          .silent_for = s.silent_for(now),
          .counts = {.good_replies = h.good_replies,
                     .timeouts = h.timeouts,
                     .bad_frames = h.bad_frames,
                     .refusals = h.error_replies}};
}

}  // namespace

CellDevices::CellDevices(const config::CellConfig& cell, DeviceLinks links) : cell_(cell) {
  if (links.scu && cell.scu) scu_ = std::make_unique<scu::Session>(*links.scu, cell.scu->session);
  if (links.spindle && cell.spindle)
    spindle_ = std::make_unique<spindle::Session>(*links.spindle, cell.spindle->session);
  if (links.encoder && cell.encoder)
    encoder_ = std::make_unique<encoder::Session>(*links.encoder, cell.encoder->session);
  sessions_[slot(cell::Device::scu)] = scu_.get();
  sessions_[slot(cell::Device::spindle)] = spindle_.get();
  sessions_[slot(cell::Device::encoder)] = encoder_.get();
}

void CellDevices::activate(link::TimePoint now) {
  for (auto* s : sessions_)
    if (s) s->activate(now);
}

void CellDevices::deactivate(link::TimePoint now) {
  for (auto* s : sessions_)
    if (s) s->deactivate(now);
}

void CellDevices::receive(link::TimePoint now) {
  for (auto* s : sessions_)
    if (s) s->receive(now);
}

void CellDevices::transmit(link::TimePoint now) {
  for (auto* s : sessions_)
    if (s) s->transmit(now);
}

bool CellDevices::all_inactive() const noexcept {
  for (const auto* s : sessions_)
    if (s && !s->quiet()) return false;
  return true;
}

void CellDevices::read(link::TimePoint now, cell::CellState& out) {
  out.now = now;
  out.axis_count = static_cast<std::uint8_t>(cell_.axes.size());
  for (auto& l : out.links)
    l = {.active = true, .fault = false, .silent_for = {}, .counts = {}};  // absent devices: no rule
  for (std::size_t d = 0; d < cell::kDevices; ++d)
    if (sessions_[d]) out.links[d] = link_state(*sessions_[d], now);

  if (scu_) {
    const auto& snap = scu_->snapshot();
    out.scu_errors = {.word = snap.errors.raw(),
                      .first_bit = snap.errors.first(),
                      .first_cause = snap.errors.any() ? scu::ErrorWord::cause(snap.errors.first()) : ""};
    out.scu_position_age = snap.position_age;
    out.scu_remote = snap.remote_open && scu_->lifecycle() == link::Lifecycle::active;
    out.scu_status2_known = snap.status2_known;
    out.scu_refusal = snap.last_refusal ? scu::describe(snap.last_refusal->status) : std::string_view{};
    for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
      const auto& axis = cell_.axes[i];
      const auto& act = snap.actuators[static_cast<std::size_t>(axis.actuator - 1)];
      const auto& fn = snap.functions[static_cast<std::size_t>(axis.function - 1)];
      auto& st = out.axes[i];
      st.present = act.status.present;
      st.scu_mm = act.position_mm;
      st.moving = act.status.motion_active;
      st.commanded = fn.execution_open || fn.outcome == scu::MoveOutcome::queued;
      st.move_refused = fn.outcome == scu::MoveOutcome::refused;
      st.moves_taken = fn.executions;
      st.scu_initialised = act.initialised;
      st.at_retracted_end = act.status.in_position;
      st.at_extended_end = act.status.out_position;
      st.actuator_fault = act.fault;
    }
  }

  if (encoder_) {
    const auto& e = encoder_->snapshot();
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

  if (spindle_) {
    const auto& s = spindle_->snapshot();
    auto& sp = out.spindle;
    sp.active = spindle_->lifecycle() == link::Lifecycle::active;
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
}

void CellDevices::apply_axes(const cell::Intents& in) {
  if (!scu_ || scu_->lifecycle() != link::Lifecycle::active) return;
  const auto& snap = scu_->snapshot();
  const bool immediate = in.halt == cell::Halt::immediate;
  if (immediate) {
    // Category 0: F20 at once (the session puts it ahead of everything and drops queued moves);
    // sent again if the SCU refused it.
    const bool f20_pending = estop_requested_ && snap.refusals == estop_refusals_;
    if (!snap.emergency_stop_open && !f20_pending && scu_->emergency_stop()) {
      estop_requested_ = true;
      estop_refusals_ = snap.refusals;
    }
  } else {
    estop_requested_ = false;
    bool motion_wanted = false;
    for (const auto& a : in.axes) motion_wanted = motion_wanted || a.move;
    // The emergency stop holds until motion is asked for again, i.e. after a reset.
    if (snap.emergency_stop_open) {
      if (motion_wanted) (void)scu_->release_emergency_stop();
      return;
    }
  }

  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    const auto& axis = cell_.axes[i];
    const auto& intent = in.axes[i];
    auto& cmd = axis_cmd_[i];
    const auto& fn = snap.functions[static_cast<std::size_t>(axis.function - 1)];
    // A move just sent shows no motion until the next RC reply: it must be stopped all the same.
    const bool busy = snap.actuators[static_cast<std::size_t>(axis.actuator - 1)].status.motion_active ||
                      fn.execution_open || fn.outcome == scu::MoveOutcome::queued;
    // One stop per motion, sent again after a new refusal; a soft one still pending is made fast
    // (the session re-encodes a queued RS in place) when a fast one is asked for.
    const auto request_stop = [&](bool soft) {
      const bool pending = cmd.stop_sent && snap.refusals == cmd.stop_refusals && (soft || !cmd.stop_soft);
      if (!pending && scu_->stop(axis.function, soft)) {
        cmd.stop_sent = true;
        cmd.stop_soft = soft;
        cmd.stop_refusals = snap.refusals;
      }
    };
    if (immediate || in.halt == cell::Halt::controlled || !intent.move) {
      // Every axis gets its own stop too (fast under category 0): a refused F20 leaves none running.
      if (busy) request_stop(!immediate);
      if (!busy) cmd.stop_sent = false;
      continue;
    }
    if (intent.move_id != cmd.applied_move) {
      // A new target while the function's RE is still open (the axis moving, say): the manual wants
      // every RE closed by its RS before the next, so a soft RS goes first. The SCU ramps down until
      // the new RE (RS, two RT and the RE on the line: some 30 ms at 38400 baud, with a keep-alive
      // between them), which takes the axis on from that speed.
      if (fn.execution_open || fn.outcome == scu::MoveOutcome::queued) {
        request_stop(true);
        continue;
      }
      const scu::ActuatorTarget target{axis.actuator, intent.target_mm};
      // Refused while the RS is still on its way: tried again next cycle.
      if (scu_->move_to(axis.function, std::span(&target, 1), intent.speed_mm_s, intent.soft)) {
        cmd.applied_move = intent.move_id;
        cmd.stop_sent = false;
      }
    } else if (busy) {
      (void)scu_->set_speed(axis.function, intent.speed_mm_s);  // sends only a changed percentage
    }
  }
}

void CellDevices::apply_spindle(const cell::Intents& in) {
  if (!spindle_ || spindle_->lifecycle() != link::Lifecycle::active) return;
  if (in.spindle.reset) (void)spindle_->reset();
  const auto& s = spindle_->snapshot();
  // A controlled hold (category 2) keeps the spindle running; stops take `run` away themselves.
  const bool run = in.spindle.run && in.halt != cell::Halt::immediate;
  const auto dir =
      in.spindle.clockwise ? spindle::Direction::clockwise : spindle::Direction::counter_clockwise;
  const bool reversing = dir != s.direction;
  if (!run || (s.run_requested && reversing)) {
    if (s.run_requested) (void)spindle_->stop();
    return;
  }
  if (!s.run_requested) {
    // After a change of direction the motor runs down to rest before it starts the other way.
    if (reversing && !s.at_rest) return;
    (void)spindle_->start(in.spindle.frequency_hz, dir);
  } else if (in.spindle.frequency_hz != s.requested_frequency_hz) {
    (void)spindle_->set_frequency(in.spindle.frequency_hz);
  }
}

void CellDevices::apply_encoder(const cell::Intents& in) {
  if (!encoder_) return;
  // The outcome of the preset in flight: the handshake ends (done or failed) a few exchanges later.
  if (preset_.sent && !preset_.done && !preset_.failed) {
    const auto& cmd = encoder_->snapshot().command;
    if (cmd.kind == encoder::Handshake::Kind::preset && cmd.phase == encoder::Handshake::Phase::done) {
      preset_.done = true;
      encoder_->clear_command();
    } else if (cmd.kind == encoder::Handshake::Kind::preset &&
               cmd.phase == encoder::Handshake::Phase::failed) {
      preset_.failed = true;
      preset_.failure = cmd.failure;
      encoder_->clear_command();
    }
  }
  if (in.encoder.preset_id == 0 || in.encoder.preset_id == preset_.id) return;
  preset_ = Preset{};
  preset_.id = in.encoder.preset_id;
  const double counts = in.encoder.preset_mm * encoder_->counts_per_mm();
  if (encoder_->lifecycle() != link::Lifecycle::active || counts < 0.0 ||
      !encoder_->preset(static_cast<std::uint32_t>(std::lround(counts)))) {
    preset_.failed = true;
    preset_.failure =
        "the encoder session refused the preset (not in data exchange, a command running, or the value "
        "beyond the measuring range)";
    return;
  }
  preset_.sent = true;
}

void CellDevices::apply(const cell::Intents& in) {
  apply_axes(in);
  apply_spindle(in);
  apply_encoder(in);
}

}  // namespace cellctl::runtime

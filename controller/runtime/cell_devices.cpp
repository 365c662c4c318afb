#include "runtime/cell_devices.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::runtime {
namespace {

constexpr std::uint16_t kStatus2Group = 0x00E0;  // actuator status 2, A1..A6: bit 0 = initialised
constexpr auto kHomedReadPeriod = std::chrono::seconds(2);

// Silence counts from the last good reply, or from activation while there was none yet.
cell::LinkState link_state(link::Lifecycle lc, const link::LinkHealth& h, link::TimePoint now,
                           link::TimePoint activated) {
  cell::LinkState l;
  l.active = lc == link::Lifecycle::active;
  l.fault = lc == link::Lifecycle::fault;
  l.silent_for = h.silent_for(now, activated);
  return l;
}

}  // namespace

CellDevices::CellDevices(const config::CellConfig& cell, DeviceLinks links) : cell_(cell) {
  if (links.scu && cell.scu) scu_ = std::make_unique<scu::Session>(*links.scu, cell.scu->session);
  if (links.spindle && cell.spindle)
    spindle_ = std::make_unique<spindle::Session>(*links.spindle, cell.spindle->session);
  if (links.encoder && cell.encoder)
    encoder_ = std::make_unique<encoder::Session>(*links.encoder, cell.encoder->session);
}

void CellDevices::activate(link::TimePoint now) {
  if (scu_) scu_->activate(now);
  if (spindle_) spindle_->activate(now);
  if (encoder_) encoder_->activate(now);
  next_homed_read_ = now;
  activated_at_ = now;
}

void CellDevices::deactivate(link::TimePoint now) {
  if (scu_) scu_->deactivate(now);
  if (spindle_) spindle_->deactivate(now);
  if (encoder_) encoder_->deactivate(now);
}

void CellDevices::poll(link::TimePoint now) {
  if (scu_) (void)scu_->poll(now);
  if (spindle_) (void)spindle_->poll(now);
  if (encoder_) (void)encoder_->poll(now);
  poll_homed(now);
}

bool CellDevices::all_inactive() const noexcept {
  const auto quiet = [](link::Lifecycle s) {
    return s == link::Lifecycle::inactive || s == link::Lifecycle::fault;
  };
  return (!scu_ || quiet(scu_->state())) && (!spindle_ || quiet(spindle_->lifecycle())) &&
         (!encoder_ || quiet(encoder_->snapshot().lifecycle));
}

void CellDevices::poll_homed(link::TimePoint now) {
  if (!scu_ || scu_->state() != link::Lifecycle::active) return;
  const auto& r = scu_->snapshot().last_read;
  if (r.sequence != homed_read_sequence_) {
    homed_read_sequence_ = r.sequence;
    if (r.valid && r.data_id == kStatus2Group) {
      homed_bits_ = 0;
      for (std::size_t a = 0; a < r.value.size() && a < cell::kMaxAxes; ++a)
        if ((r.value[a] & 0x01u) != 0) homed_bits_ = static_cast<std::uint8_t>(homed_bits_ | (1u << a));
    }
  }
  if (now >= next_homed_read_ && scu_->read(kStatus2Group)) next_homed_read_ = now + kHomedReadPeriod;
}

void CellDevices::read(link::TimePoint now, cell::CellState& out) {
  out.now = now;
  out.axis_count = static_cast<std::uint8_t>(cell_.axes.size());
  for (auto& l : out.links)
    l = {.active = true, .fault = false, .silent_for = {}};  // absent devices: no rule

  if (scu_) {
    const auto& snap = scu_->snapshot();
    out.links[static_cast<std::size_t>(cell::Device::scu)] =
        link_state(scu_->state(), scu_->health(), now, activated_at_);
    out.scu_error_word = snap.errors.raw();
    out.scu_position_age = snap.last_refresh ? now - *snap.last_refresh : link::Duration{};
    out.scu_remote = snap.remote_open && scu_->state() == link::Lifecycle::active;
    out.scu_status2_known = status2_known_;
    out.scu_refusal = snap.last_refusal ? scu::describe(snap.last_refusal->status) : std::string_view{};
    for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
      const auto& axis = cell_.axes[i];
      const auto a = static_cast<std::size_t>(axis.actuator - 1);
      const auto& act = snap.actuators[a];
      auto& st = out.axes[i];
      st.present = act.status.present;
      st.scu_mm = act.position_edges / axis.edges_per_mm;
      st.moving = act.status.motion_active;
      const auto& fn = snap.functions[static_cast<std::size_t>(axis.function - 1)];
      st.commanded = fn.execution_open || fn.outcome == scu::MoveOutcome::queued;
      st.move_refused = fn.outcome == scu::MoveOutcome::refused;
      st.homed = ((static_cast<unsigned>(homed_bits_) >> a) & 1u) != 0;
      st.actuator_fault = snap.errors.actuator_fault(axis.actuator);
    }
  }

  if (encoder_) {
    const auto& e = encoder_->snapshot();
    auto& enc = out.encoder;
    out.links[static_cast<std::size_t>(cell::Device::encoder)] =
        link_state(e.lifecycle, encoder_->health(), now, activated_at_);
    enc.data_exchange = e.data_exchange;
    // input_valid covers the Ready bit and inputs the manual does not allow (never a stale position).
    enc.ready = e.data_exchange && e.input_valid;
    enc.alarm = e.diagnosis && e.diagnosis->alarms != 0;
    enc.limit_switch = e.has_status_bits && e.status.limit_switch;
    // A diagnosis the encoder raised (DH) during data exchange: a pulse the monitor latches.
    enc.diagnosis_pending = e.diagnosis_reads != encoder_diag_reads_ && e.data_exchange;
    encoder_diag_reads_ = e.diagnosis_reads;
    enc.mm = e.position_mm;
    enc.mm_s = e.velocity_mm_s;
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
    out.links[static_cast<std::size_t>(cell::Device::spindle)] =
        link_state(spindle_->lifecycle(), spindle_->health(), now, activated_at_);
    sp.active = spindle_->lifecycle() == link::Lifecycle::active;
    const double sign = s.direction == spindle::Direction::clockwise ? 1.0 : -1.0;
    sp.set_hz = s.requested_frequency_hz;
    // STILLSTAND comes with every fast status poll, the frequency only with the slower value poll.
    sp.at_rest = !s.status_valid || s.at_rest;
    sp.actual_hz = sp.at_rest ? 0.0 : sign * s.actual_frequency_hz;
    sp.running = spindle_running_;
    sp.at_speed = s.status_valid && s.at_speed;
    if (!sp.at_speed)
      at_speed_since_.reset();
    else if (!at_speed_since_)
      at_speed_since_ = now;
    // Two value polls and a reply time after N_Soll_OK, the frequency reading is a fresh one.
    const auto settle = 2 * cell_.spindle->session.values_poll + cell_.spindle->session.reply_timeout;
    sp.settled = at_speed_since_ && now - *at_speed_since_ > settle;
    sp.warning = s.warning();
    sp.fault = s.fault();
    sp.fault_number = s.fault() ? s.error_number : 0;
    sp.over_temperature = s.motor_over_temperature;
    sp.current_limit = s.current_limit;
    sp.start_refused = s.start_refused;
    sp.error_number = s.error_number;
  }
}

std::uint16_t CellDevices::percent(std::size_t axis, double mm_s) const noexcept {
  const double full = cell_.axes[axis].full_speed_mm_s;
  return static_cast<std::uint16_t>(std::clamp(std::lround(100.0 * mm_s / full), 1L, 100L));
}

void CellDevices::apply_axes(const cell::Intents& in) {
  if (!scu_ || scu_->state() != link::Lifecycle::active) return;
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
    if (immediate || in.halt == cell::Halt::controlled || !intent.move) {
      // Every axis gets its own stop too (fast under category 0): a refused F20 leaves none running.
      const bool stop_pending = cmd.stop_sent && snap.refusals == cmd.stop_refusals;
      if (busy && !stop_pending && scu_->stop(axis.function, !immediate)) {
        cmd.stop_sent = true;
        cmd.stop_refusals = snap.refusals;
      }
      if (!busy) cmd.stop_sent = false;
      continue;
    }
    const auto pct = percent(i, intent.speed_mm_s);
    if (intent.move_id != cmd.applied_move) {
      const scu::ActuatorTarget target{
          axis.actuator, static_cast<std::int32_t>(std::lround(intent.target_mm * axis.edges_per_mm))};
      // Refused while the function's previous RE is still open: tried again next cycle.
      if (scu_->move_to(axis.function, std::span(&target, 1), pct, intent.soft)) {
        cmd.applied_move = intent.move_id;
        cmd.speed_percent = pct;
        cmd.stop_sent = false;
      }
    } else if (busy && pct != cmd.speed_percent && scu_->set_speed(axis.function, pct)) {
      cmd.speed_percent = pct;
    }
  }
}

void CellDevices::apply_spindle(const cell::Intents& in) {
  if (!spindle_ || spindle_->lifecycle() != link::Lifecycle::active) return;
  if (in.spindle.reset) (void)spindle_->reset();
  // A controlled hold (category 2) keeps the spindle running; stops take `run` away themselves.
  const bool run = in.spindle.run && in.halt != cell::Halt::immediate;
  const bool reversing = in.spindle.clockwise != spindle_cw_;
  if (!run || (spindle_running_ && reversing)) {
    if (spindle_running_ && spindle_->stop()) spindle_running_ = false;
    return;
  }
  if (!spindle_running_) {
    // After a change of direction the motor runs down to rest before it starts the other way.
    if (reversing && !spindle_->snapshot().at_rest) return;
    const auto dir =
        in.spindle.clockwise ? spindle::Direction::clockwise : spindle::Direction::counter_clockwise;
    if (spindle_->start(in.spindle.frequency_hz, dir)) {
      spindle_running_ = true;
      spindle_hz_ = in.spindle.frequency_hz;
      spindle_cw_ = in.spindle.clockwise;
    }
  } else if (in.spindle.frequency_hz != spindle_hz_ && spindle_->set_frequency(in.spindle.frequency_hz)) {
    spindle_hz_ = in.spindle.frequency_hz;
  }
}

void CellDevices::apply(const cell::Intents& in, link::TimePoint) {
  apply_axes(in);
  apply_spindle(in);
}

}  // namespace cellctl::runtime

#include "device_seam/scu_device.hpp"

#include <fmt/format.h>

namespace cellctl::device_seam {

ScuDevice::ScuDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link, Reopen reopen)
    : CellDevice(slot, "scu", "SCU", std::move(reopen)), cell_(cell), session_(link, cell.scu->session) {}

const scu::ActuatorState& ScuDevice::actuator_of(const scu::Snapshot& snap, std::size_t axis) const {
  return snap.actuators[static_cast<std::size_t>(cell_.axes[axis].actuator - 1)];
}

void ScuDevice::read(link::TimePoint, cell::CellState& out) {
  const auto& snap = session_.snapshot();
  out.scu_errors = {.word = snap.errors.raw(),
                    .first_bit = snap.errors.first(),
                    .first_cause = snap.errors.any() ? scu::ErrorWord::cause(snap.errors.first()) : ""};
  out.scu_position_age = snap.position_age;
  out.scu_remote = snap.remote_open && session_.lifecycle() == link::Lifecycle::active;
  out.scu_status2_known = snap.status2_known;
  out.scu_refusal = snap.last_refusal ? scu::describe(snap.last_refusal->status) : std::string_view{};
  for (std::size_t i = 0; i < cell_.axes.size(); ++i)
    if (axis_cmd_[i].refused_move != 0) out.scu_refusal = to_string(axis_cmd_[i].refusal);
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    const auto& act = actuator_of(snap, i);
    const auto& fn = snap.functions[static_cast<std::size_t>(cell_.axes[i].function - 1)];
    auto& st = out.axes[i];
    st.present = act.status.present;
    st.scu_mm = act.position_mm;
    st.moving = act.status.motion_active;
    st.commanded = fn.execution_open || fn.outcome == scu::MoveOutcome::queued;
    st.move_refused = fn.outcome == scu::MoveOutcome::refused || axis_cmd_[i].refused_move != 0;
    st.moves_taken = fn.executions;
    st.scu_initialised = act.initialised;
    st.at_retracted_end = act.status.in_position;
    st.at_extended_end = act.status.out_position;
    st.actuator_fault = act.fault;
  }
}

void ScuDevice::halt_immediately(const scu::Snapshot& snap) {
  // Category 0: F20 at once (the session puts it ahead of everything and drops queued moves); sent
  // again if the SCU refused it.
  const bool f20_pending = estop_requested_ && snap.refusals == estop_refusals_;
  if (!snap.emergency_stop_open && !f20_pending && session_.emergency_stop()) {
    estop_requested_ = true;
    estop_refusals_ = snap.refusals;
  }
}

void ScuDevice::apply(const cell::Intents& in) {
  if (session_.lifecycle() != link::Lifecycle::active) return;
  const auto& snap = session_.snapshot();
  if (in.halt == cell::Halt::immediate) {
    halt_immediately(snap);
  } else {
    estop_requested_ = false;
    bool motion_wanted = false;
    for (const auto& a : in.axes) motion_wanted = motion_wanted || a.move;
    // The emergency stop holds until motion is asked for again, i.e. after a reset.
    if (snap.emergency_stop_open) {
      // Refused only while the session is not active (it is, above) or the queue is full: asked again
      // next cycle; one release goes out however often it is asked.
      if (motion_wanted) (void)session_.release_emergency_stop();
      return;
    }
  }
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) apply_axis(i, in, snap);
}

void ScuDevice::apply_axis(std::size_t i, const cell::Intents& in, const scu::Snapshot& snap) {
  const auto& axis = cell_.axes[i];
  const auto& intent = in.axes[i];
  auto& cmd = axis_cmd_[i];
  const bool immediate = in.halt == cell::Halt::immediate;
  const auto& fn = snap.functions[static_cast<std::size_t>(axis.function - 1)];
  // A move just sent shows no motion until the next RC reply: it must be stopped all the same.
  const bool busy = actuator_of(snap, i).status.motion_active || fn.execution_open ||
                    fn.outcome == scu::MoveOutcome::queued;
  // One stop per motion, sent again after a new refusal; a soft one still pending is made fast (the
  // session re-encodes a queued RS in place) when a fast one is asked for.
  const auto request_stop = [&](bool soft) {
    const bool pending = cmd.stop_sent && snap.refusals == cmd.stop_refusals && (soft || !cmd.stop_soft);
    if (!pending && session_.stop(axis.function, soft)) {
      cmd.stop_sent = true;
      cmd.stop_soft = soft;
      cmd.stop_refusals = snap.refusals;
    }
  };
  if (immediate || in.halt == cell::Halt::controlled || !intent.move) {
    // Every axis gets its own stop too (fast under category 0): a refused F20 leaves none running.
    if (busy) request_stop(!immediate);
    if (!busy) cmd.stop_sent = false;
    return;
  }
  if (intent.move_id != cmd.applied_move) {
    if (intent.move_id == cmd.refused_move) return;  // refused for good: not asked again every cycle
    cmd.refused_move = 0;                            // (an earlier move's refusal)
    // A new target while the function's RE is still open (the axis moving, say): the manual wants every
    // RE closed by its RS before the next, so a soft RS goes first. The SCU ramps down until the new RE
    // (RS, two RT and the RE on the line: some 30 ms at 38400 baud, with a keep-alive between them),
    // which takes the axis on from that speed.
    if (fn.execution_open || fn.outcome == scu::MoveOutcome::queued) {
      request_stop(true);
      return;
    }
    const scu::ActuatorTarget target{axis.actuator, intent.target_mm};
    const auto r = session_.move_to(axis.function, std::span(&target, 1), intent.speed_mm_s, intent.soft);
    if (r) {
      cmd.applied_move = intent.move_id;
      cmd.stop_sent = false;
    } else if (!r.worth_retrying()) {
      cmd.refused_move = intent.move_id;
      cmd.refusal = r.status;
    }  // else refused while the RS is still on its way or the queue is full: tried again next cycle
  } else if (busy) {
    // Sends only a changed percentage. Refused while the queue is full (the percentage in force is
    // compared anew next cycle), or for a speed not above 0, which the move executor never asks for.
    (void)session_.set_speed(axis.function, intent.speed_mm_s);
  }
}

// --- the safe-stop ---

bool ScuDevice::all_at_rest() const noexcept {
  const auto& snap = session_.snapshot();
  if (!snap.last_refresh) return false;
  for (const auto& a : snap.actuators)
    if (a.configured && a.status.motion_active) return false;
  return true;
}

void ScuDevice::observe(link::TimePoint now, const cell::CellState& state) noexcept {
  note_loss(now);
  const auto& snap = session_.snapshot();
  if (snap.last_refresh && snap.last_refresh != stop_.last_refresh) {
    stop_.last_refresh = snap.last_refresh;
    for (std::size_t i = 0; i < cell_.axes.size() && i < cell::kMaxAxes; ++i)
      stop_.last_mm[i] = actuator_of(snap, i).position_mm;
  }
  if (state.encoder.data_exchange && state.links[cell::slot(cell::Device::encoder)].active) {
    stop_.measured_at = now;
    stop_.measured_mm = state.encoder.mm;
    stop_.measured_mm_s = state.encoder.mm_s;
  }
}

void ScuDevice::begin_stop(link::TimePoint now) {
  session_.deactivate(now);
}  // RS, RA

void ScuDevice::step_stop(link::TimePoint now, const StopContext& ctx) {
  if (resolved()) return;
  const auto& snap = session_.snapshot();
  const bool lost = lost_at().has_value();
  if (lost) {
    stop_.bound_at = std::max(stop_.bound_at,
                              session_.last_sent() + scu::kWatchdogPeriod + session_.config().stopping_time);
    if (!stop_.give_up) stop_.give_up = stop_.bound_at;  // no new attempt after the first bound
  }
  switch (session_.lifecycle()) {
    case link::Lifecycle::fault:
      if (now >= stop_.bound_at) return resolve(Safe::bounded, now);
      if (now < *stop_.give_up) recover(now);
      return;
    case link::Lifecycle::activating:
      if (lost && now >= stop_.bound_at) resolve(Safe::bounded, now);
      return;
    case link::Lifecycle::active:
      // Back after a loss: F20 stops every actuator, and a refresh after it shows them at rest.
      if (!stop_.f20_asked) stop_.f20_asked = static_cast<bool>(session_.emergency_stop());
      if (snap.emergency_stop_open && !stop_.refreshes_at_f20) stop_.refreshes_at_f20 = snap.refreshes;
      if (stop_.refreshes_at_f20 && snap.refreshes > *stop_.refreshes_at_f20 && all_at_rest()) {
        stop_.rest_seen_at = now;
        session_.deactivate(now);
      } else if (lost && now >= stop_.bound_at) {
        resolve(Safe::bounded, now);
      }
      return;
    case link::Lifecycle::deactivating:
      if (all_at_rest() && (!lost || stop_.refreshes_at_f20)) stop_.rest_seen_at = now;
      if (ctx.begun_at && now >= *ctx.begun_at + ctx.confirm_within && !lost)
        resolve(stop_.rest_seen_at ? Safe::observed : Safe::unknown, now);
      return;
    case link::Lifecycle::inactive:
      if (!stop_.closed_at) {
        stop_.closed_at = now;
        stop_.moving_at_close = !all_at_rest();
      }
      if (!stop_.moving_at_close || stop_.rest_seen_at) return resolve(Safe::observed, now);
      // RA ends every remote motion: at rest within the stopping time, unseen.
      if (now >= *stop_.closed_at + session_.config().stopping_time) resolve(Safe::bounded, now);
      return;
  }
}

std::string ScuDevice::evidence(const StopContext& ctx) const {
  std::string positions;
  for (std::size_t i = 0; i < cell_.axes.size() && i < cell::kMaxAxes; ++i)
    positions +=
        fmt::format("{}{} {:.2f} mm", positions.empty() ? "" : ", ", cell_.axes[i].name, stop_.last_mm[i]);
  std::string out = loss_evidence("SCU", ctx);
  switch (resolved().value_or(Safe::unknown)) {
    case Safe::observed:
      out += lost_at()
                 ? fmt::format("F20 sent after it came back; every actuator reported at rest at {:.3f} s",
                               ctx.t_of(stop_.rest_seen_at.value_or(resolved_at())))
                 : fmt::format("every actuator reported at rest, remote mode closed at {:.3f} s",
                               ctx.t_of(stop_.closed_at.value_or(resolved_at())));
      break;
    case Safe::bounded:
      out += stop_.closed_at
                 ? fmt::format(
                       "remote mode closed at {:.3f} s while an actuator still moved; at rest by {:.3f} s "
                       "(stopping time)",
                       ctx.t_of(*stop_.closed_at), ctx.t_of(resolved_at()))
                 : fmt::format(
                       "stop not confirmed; the SCU's communication time-out ({:.1f} s after the last "
                       "request) and "
                       "the actuators' stopping time had passed at {:.3f} s: its own protection stopped them",
                       link::to_seconds(scu::kWatchdogPeriod), ctx.t_of(stop_.bound_at));
      break;
    case Safe::unknown:
      out += "actuators still reported moving when the safe-stop ended";
      break;
  }
  out += "; last SCU positions";
  out += stop_.last_refresh ? fmt::format(" ({:.3f} s): {}", ctx.t_of(*stop_.last_refresh), positions)
                            : ": none";
  for (const auto& a : cell_.axes)
    if (a.encoder && stop_.measured_at)
      out += fmt::format("; last measured {} {:.2f} mm at {:.3f} s ({:.2f} mm/s)", a.name, stop_.measured_mm,
                         ctx.t_of(*stop_.measured_at), stop_.measured_mm_s);
  return out;
}

}  // namespace cellctl::device_seam

// scu::Session: what it makes of each reply — an acknowledge, a refusal, a cyclic refresh, the actuators'
// status 2 — and when an execution it started has finished.
#include <cmath>
#include <cstdlib>

#include "scu/data_list.hpp"
#include "scu/session.hpp"

namespace cellctl::scu {

void Session::on_reply(const Reply& reply, link::TimePoint now) {
  if (!in_flight_) return;
  // Only an ACK is a sign of a healthy link: an SCU that answers every request with an error (after a
  // watchdog lapse, say) must go silent in the link's eyes and fault, not pass for alive.
  if (reply.status == Status::ack) health_.record_reply(sent_at_, now);
  if (reply.status == Status::checksum_error) {
    // The SCU saw our request damaged: the same request again.
    ++health_.error_replies;
    retry_or_give_up(now, "answers CSE (checksum error) every time");
    return;
  }
  const Pending done = *in_flight_;
  in_flight_.reset();
  replies_.expect_nothing();
  if (reply.status == Status::ack) {
    on_ack(reply, done, now);
  } else {
    on_refusal(reply, done);
  }
}

void Session::on_ack(const Reply& reply, const Pending& p, link::TimePoint now) {
  auto& fs = snapshot_.functions[p.function < kMotionFunctionCount ? p.function : 0];
  switch (p.purpose) {
    case Purpose::open:
      snapshot_.remote_open = true;
      break;
    case Purpose::first_keepalive:
      break;
    case Purpose::setup_cyclic:
      keepalive_armed_ = true;
      last_keepalive_sent_ = now - config_.keepalive_period;  // the first refresh at once
      break;
    case Purpose::keepalive:
      on_refresh(reply.data, now);
      break;
    case Purpose::position:
      break;
    case Purpose::speed:
      break;
    case Purpose::execute:
      fs.execution_open = true;
      fs.outcome = MoveOutcome::running;
      ++fs.executions;
      execute_mark_[p.function] = snapshot_.refreshes;
      break;
    case Purpose::stop:
      fs.execution_open = false;
      stop_queued_.reset(p.function);
      if (fs.outcome == MoveOutcome::running || fs.outcome == MoveOutcome::queued)
        fs.outcome = MoveOutcome::stopped_short;
      break;
    case Purpose::emergency_stop:
      snapshot_.emergency_stop_open = true;
      f20_refused_ = false;
      break;
    case Purpose::release_emergency:
      snapshot_.emergency_stop_open = false;
      break;
    case Purpose::read:
      snapshot_.last_read.data_id = p.data_id;
      // (The reply's shape keeps its data within kMaxReplyData, the value's capacity.)
      snapshot_.last_read.valid = snapshot_.last_read.value.assign(reply.data);
      snapshot_.last_read.status = Status::ack;
      ++snapshot_.last_read.sequence;
      break;
    case Purpose::status2:
      on_status2(reply.data);
      break;
    case Purpose::close:
      snapshot_.remote_open = false;
      enter(link::Lifecycle::inactive);
      break;
  }
}

void Session::on_status2(std::span<const std::uint8_t> data) {
  status2_queued_ = false;
  for (std::size_t a = 0; a < kActuatorCount && a < data.size(); ++a)
    snapshot_.actuators[a].initialised = Status2::from_byte(data[a]).initialized;
  snapshot_.status2_known = true;
}

void Session::on_refusal(const Reply& reply, const Pending& p) {
  ++health_.error_replies;
  ++snapshot_.refusals;
  snapshot_.last_refusal = Refusal{reply.command, reply.status};
  switch (p.purpose) {
    case Purpose::open:
    case Purpose::first_keepalive:
    case Purpose::setup_cyclic:
    case Purpose::close:
      fault(
          "SCU {} refused with {} ({}) while {} remote mode: check safety_id and the SCU's parameterization, "
          "then activate again",
          to_string(reply.command), to_string(reply.status), describe(reply.status),
          lifecycle() == link::Lifecycle::deactivating ? "leaving" : "entering");
      return;
    case Purpose::keepalive:
      // Remote mode is gone (watchdog lapse with Safety_ID 0, or the SCU was reset): it must be opened again.
      fault("SCU {} refused with {} ({}) on the keep-alive: remote mode was lost (watchdog?); activate again",
            to_string(reply.command), to_string(reply.status), describe(reply.status));
      return;
    case Purpose::position:
    case Purpose::speed:
    case Purpose::execute:
      snapshot_.functions[p.function].outcome = MoveOutcome::refused;
      drop_queued_moves(p.function);
      return;
    case Purpose::stop:
      stop_queued_.reset(p.function);
      return;
    case Purpose::emergency_stop:
      f20_refused_ = true;
      return;
    case Purpose::release_emergency:
      return;
    case Purpose::read:
      snapshot_.last_read.data_id = p.data_id;
      snapshot_.last_read.valid = false;
      snapshot_.last_read.status = reply.status;
      snapshot_.last_read.value.clear();
      ++snapshot_.last_read.sequence;
      return;
    case Purpose::status2:
      status2_queued_ = false;  // asked again at the next period
      return;
  }
}

void Session::on_refresh(std::span<const std::uint8_t> data, link::TimePoint now) {
  CyclicRefresh r;
  if (!layout_.decode(data, r)) {
    ++health_.bad_frames;
    return;
  }
  for (std::size_t a = 0; a < kActuatorCount; ++a) {
    if (!config_.actuators.test(a)) continue;
    auto& act = snapshot_.actuators[a];
    act.position_edges = r.positions[a];
    act.position_mm = r.positions[a] / config_.specs[a].edges_per_mm;
    act.status = r.status[a];
    act.fault = r.errors.actuator_fault(static_cast<int>(a) + 1);
  }
  snapshot_.errors = r.errors;
  if (r.errors.remote_timeout()) snapshot_.watchdog_lapse_seen = true;
  ++snapshot_.refreshes;
  snapshot_.last_refresh = now;
  // The positions are from some instant between the RC's sending and its reply: their age counts from
  // the sending, so a slow line (a USB adapter, a delay) is counted in it, not mistaken for motion.
  positions_asked_at_ = sent_at_;
  snapshot_.position_age = now - sent_at_;
  if (lifecycle() == link::Lifecycle::activating) enter(link::Lifecycle::active);
  close_finished_executions();
}

void Session::close_finished_executions() {
  for (std::size_t f = 0; f < kMotionFunctionCount; ++f) {
    auto& fs = snapshot_.functions[f];
    if (!fs.execution_open || stop_queued_.test(f) || snapshot_.refreshes <= execute_mark_[f]) continue;
    const auto& fn = config_.functions[f];
    bool moving = false, on_target = fs.outcome == MoveOutcome::running;
    for (int a = 1; a <= kActuatorCount; ++a) {
      if (!fn.moves(a)) continue;
      const auto& act = snapshot_.actuators[static_cast<std::size_t>(a - 1)];
      moving = moving || act.status.motion_active;
      if (fs.targeted.test(static_cast<std::size_t>(a - 1)) &&
          std::abs(act.position_edges - fs.targets[static_cast<std::size_t>(a - 1)]) >
              config_.arrival_tolerance_edges)
        on_target = false;
    }
    if (moving) continue;
    // The motion ended (at the target, stopped, or never started because the speed was below the
    // actuator's threshold): the manual wants the RE closed with RS in every case.
    if (fs.outcome == MoveOutcome::running)
      fs.outcome = on_target ? MoveOutcome::arrived : MoveOutcome::stopped_short;
    if (enqueue(true, StopRequest{static_cast<std::uint8_t>(f), kUnusedParam}, Purpose::stop,
                static_cast<std::uint8_t>(f)))
      stop_queued_.set(f);
  }
}

}  // namespace cellctl::scu

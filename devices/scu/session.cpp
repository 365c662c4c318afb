#include "scu/session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "scu/data_list.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::scu {

const char* to_string(MoveOutcome o) noexcept {
  switch (o) {
    case MoveOutcome::none:
      return "none";
    case MoveOutcome::queued:
      return "queued";
    case MoveOutcome::running:
      return "running";
    case MoveOutcome::arrived:
      return "arrived";
    case MoveOutcome::stopped_short:
      return "stopped short of the target";
    case MoveOutcome::refused:
      return "refused by the SCU";
  }
  return "?";
}

namespace {
// Actuator status 2 of A1..A6 (RG group): bit 0 = initialised. It is not in the cyclic object (which
// carries status 1), so it is read by itself: after the first refresh and then this often.
constexpr std::uint16_t kStatus2Group = 0x00E0;
constexpr auto kStatus2Period = std::chrono::seconds(2);
// What read_link takes from the link at a time: less than a reply, so that the reply stream (two
// replies) always takes a whole chunk beside the part of a reply it may hold.
constexpr std::size_t kReadChunk = 256;
static_assert(kReadChunk < kMaxReplyTelegram);
}  // namespace

Session::Session(link::Link& link, const SessionConfig& config)
    : link_(link), link_name_(link.describe()), config_(config), layout_(config.actuators) {
  validate(config_);
  for (std::size_t a = 0; a < kActuatorCount; ++a)
    snapshot_.actuators[a].configured = config_.actuators.test(a);
  keepalive_.purpose = Purpose::keepalive;
  const CyclicRequest rc{0, {}};
  (void)encode_request(rc, keepalive_.bytes);  // an RC without data always fits its buffer
  keepalive_.shape = reply_shape(rc);
  // Should the process die of a fatal signal, the port gets an F20: every actuator stops at once
  // (link/crash_stop.hpp). The SCU's own communication time-out would stop them too, 0.5 s later.
  RequestBytes f20;
  if (encode_request(ExecuteRequest{kEmergencyStopFnc, kUnusedParam, kUnusedParam}, f20))
    link_.arm_crash_stop(f20.view());
}

bool Session::defined(int function) const noexcept {
  return function >= 1 && function <= kMotionFunctionCount &&
         config_.functions[static_cast<std::size_t>(function - 1)].defined;
}

bool Session::enqueue(bool urgent, const Request& r, Purpose p, std::uint8_t function,
                      std::uint16_t data_id) {
  Pending pending;
  if (!encode_request(r, pending.bytes)) return false;
  pending.shape = reply_shape(r);
  pending.purpose = p;
  pending.function = function;
  pending.data_id = data_id;
  return urgent ? urgent_.push_back(pending) : normal_.push_back(pending);
}

void Session::activate(link::TimePoint now) {
  urgent_.clear();
  normal_.clear();
  in_flight_.reset();
  replies_.expect_nothing();
  snapshot_.remote_open = false;
  snapshot_.status2_known = false;
  snapshot_.last_refresh.reset();
  positions_asked_at_.reset();
  keepalive_armed_ = false;
  status2_queued_ = false;
  stop_queued_.reset();
  f20_refused_ = false;
  activated_at_ = now;
  health_.last_good.reset();
  enter(link::Lifecycle::activating, now);
  const auto object = layout_.object_value();
  // The queues were emptied above: the three fit.
  (void)enqueue(false, OpenRequest{config_.safety_id}, Purpose::open);
  (void)enqueue(false, CyclicRequest{}, Purpose::first_keepalive);
  (void)enqueue(false, TransferRequest{data_id::cyclic_object(1), object}, Purpose::setup_cyclic);
}

void Session::deactivate(link::TimePoint) {
  if (lifecycle() != link::Lifecycle::active && lifecycle() != link::Lifecycle::activating) {
    if (lifecycle() != link::Lifecycle::fault) enter(link::Lifecycle::inactive);
    return;
  }
  normal_.clear();
  status2_queued_ = false;
  enter(link::Lifecycle::deactivating);
  for (int f = 1; f <= kMotionFunctionCount; ++f) {
    auto& fs = snapshot_.functions[static_cast<std::size_t>(f - 1)];
    const bool in_flight_execute =
        in_flight_ && in_flight_->purpose == Purpose::execute && in_flight_->function == fnc(f);
    if ((fs.execution_open || in_flight_execute) && !stop_queued_.test(static_cast<std::size_t>(f - 1))) {
      if (enqueue(true, StopRequest{fnc(f), kSoftStartStop}, Purpose::stop, fnc(f)))
        stop_queued_.set(static_cast<std::size_t>(f - 1));
    }
  }
  // Neither fails: the normal queue was emptied above, and the urgent one never fills (see
  // retry_or_give_up). Should an RS or the release not fit all the same, the RA ends every remote
  // motion.
  if (snapshot_.emergency_stop_open && !on_its_way(Purpose::release_emergency))
    (void)enqueue(true, StopRequest{kEmergencyStopFnc, kUnusedParam}, Purpose::release_emergency);
  if (snapshot_.remote_open || in_flight_)
    (void)enqueue(false, AbortRequest{}, Purpose::close);
  else
    enter(link::Lifecycle::inactive);
}

void Session::receive(link::TimePoint now) {
  if (quiet()) {
    std::array<std::uint8_t, 64> sink{};
    while (link_.read(sink).count > 0) {
    }  // nobody asked: whatever arrives is stale
    return;
  }
  snapshot_.position_age = now - positions_asked_at_.value_or(activated_at_);
  read_link(now);
  if (lifecycle() == link::Lifecycle::fault) return;
  if (in_flight_ && now - sent_at_ > config_.reply_timeout) {
    ++health_.timeouts;
    retry_or_give_up(now, "no reply");
  }
  if (lifecycle() == link::Lifecycle::fault) return;
  const auto silent = silent_for(now);
  if (silent > config_.link_fault_after)
    fault(
        "SCU on {} silent for {:.0f} ms (limit {:.0f} ms): check the cable, the SCU's power, DTR/RTS and "
        "the baud rate",
        link_name_, link::to_milliseconds(silent), link::to_milliseconds(config_.link_fault_after));
}

void Session::transmit(link::TimePoint now) {
  if (quiet()) return;
  schedule_status2(now);
  if (!in_flight_) send_next(now);
}

void Session::schedule_status2(link::TimePoint now) {
  if (!accepting() || status2_queued_ || snapshot_.refreshes == 0 || now < next_status2_) return;
  if (enqueue(false, GetRequest{kStatus2Group}, Purpose::status2)) {
    status2_queued_ = true;
    next_status2_ = now + kStatus2Period;
  }
}

void Session::read_link(link::TimePoint now) {
  std::array<std::uint8_t, kReadChunk> buf{};
  for (;;) {
    const auto r = link_.read(buf);
    if (r.status != link::IoStatus::ok) {
      fault("SCU link {} {}: check the port", link_name_,
            r.status == link::IoStatus::closed ? "closed" : "failed");
      return;
    }
    if (r.count == 0) return;
    // Takes it all: the events are drained below before the next read, which leaves less than one
    // reply in a stream that holds two (kReadChunk < kMaxReplyTelegram).
    (void)replies_.feed(std::span(buf).first(r.count));
    for (auto e = replies_.next(); e.kind != ReplyStream::Event::Kind::need_more; e = replies_.next()) {
      if (e.kind == ReplyStream::Event::Kind::reply) {
        on_reply(e.reply, now);
        if (lifecycle() == link::Lifecycle::fault) return;
        continue;
      }
      ++health_.bad_frames;
      // A damaged reply to the request in flight (complete, wrong CRC): ask again at once.
      if (e.error == DecodeError::bad_crc && in_flight_) retry_or_give_up(now, "replies with a bad CRC");
      if (lifecycle() == link::Lifecycle::fault) return;
    }
  }
}

void Session::retry_or_give_up(link::TimePoint now, const char* why) {
  if (!in_flight_) return;
  const bool is_stop = in_flight_->purpose == Purpose::stop ||
                       in_flight_->purpose == Purpose::emergency_stop ||
                       in_flight_->purpose == Purpose::release_emergency;
  if (attempts_ <= config_.retries && !urgent_.empty() && !is_stop && defer_for_stop(now)) return;
  if (attempts_ <= config_.retries) {
    ++health_.retries;
    send(*in_flight_, now);
    return;
  }
  const Pending failed = *in_flight_;
  in_flight_.reset();
  replies_.expect_nothing();
  switch (failed.purpose) {
    case Purpose::open:
    case Purpose::first_keepalive:
    case Purpose::setup_cyclic:
    case Purpose::close:
      fault("SCU on {}: {} got {} after {} attempts: check the cable, the port and the baud rate", link_name_,
            to_string(failed.shape.command), why, attempts_);
      return;
    case Purpose::stop:
    case Purpose::emergency_stop:
    case Purpose::release_emergency:
      // A stop is never given up: it goes back first (the urgent queue, kQueueDepth, never fills: it holds
      // an RS per function and an F20 asked again only after a refusal); the link fault ends it if the
      // SCU is gone.
      (void)urgent_.push_front(failed);
      return;
    case Purpose::position:
    case Purpose::speed:
    case Purpose::execute:
      snapshot_.functions[failed.function].outcome = MoveOutcome::refused;
      drop_queued_moves(failed.function);
      return;
    case Purpose::status2:
      status2_queued_ = false;
      return;
    case Purpose::keepalive:
    case Purpose::read:
      return;  // the next refresh or the caller's next read will do
  }
}

bool Session::defer_for_stop(link::TimePoint now) {
  // A stop queued while this request waited for its reply must not wait for its retries as well
  // (up to retries × reply_timeout): the stop goes now, the request is tried again after it. A
  // keep-alive is not re-queued; the schedule sends the next one.
  const Pending deferred = *in_flight_;
  const bool requeue = deferred.purpose == Purpose::position || deferred.purpose == Purpose::speed ||
                       deferred.purpose == Purpose::execute || deferred.purpose == Purpose::read ||
                       deferred.purpose == Purpose::status2;
  if (!requeue && deferred.purpose != Purpose::keepalive) return false;
  if (requeue && !normal_.push_front(deferred)) return false;
  ++health_.retries;
  in_flight_.reset();
  replies_.expect_nothing();
  send_next(now);
  return true;
}

void Session::send_next(link::TimePoint now) {
  const bool keepalive_due = keepalive_armed_ && now - last_keepalive_sent_ >= config_.keepalive_period;
  // Stops first; then the watchdog's RC when due (it must never starve), but never twice in a row
  // while telegrams wait: on a slow line (an exchange longer than the keep-alive period) the RC would
  // be due after every exchange and a move would never go out. Every second exchange is an RC then,
  // at most two reply time-outs apart (2 × 150 ms, inside the SCU's 500 ms watchdog). Then the queue;
  // with a zero period the RC fills every gap instead.
  const bool queue_waits = !normal_.empty() && last_sent_keepalive_;
  if (!urgent_.empty()) {
    const Pending p = urgent_.front();
    urgent_.pop_front();
    attempts_ = 0;
    send(p, now);
  } else if (keepalive_due && config_.keepalive_period > link::Duration::zero() && !queue_waits) {
    attempts_ = 0;
    send(keepalive_, now);
  } else if (!normal_.empty()) {
    const Pending p = normal_.front();
    normal_.pop_front();
    attempts_ = 0;
    send(p, now);
  } else if (keepalive_due) {
    attempts_ = 0;
    send(keepalive_, now);
  }
}

void Session::send(const Pending& p, link::TimePoint now) {
  ++attempts_;
  in_flight_ = p;
  sent_at_ = now;
  last_sent_keepalive_ = p.purpose == Purpose::keepalive || p.purpose == Purpose::first_keepalive;
  if (last_sent_keepalive_) last_keepalive_sent_ = now;
  replies_.expect(p.shape);
  const auto bytes = p.bytes.view();
  const auto r = link_.write(bytes);
  if (r.status != link::IoStatus::ok) {
    fault("SCU link {} failed on write: check the port", link_name_);
    return;
  }
  // A short write on a serial port is treated like a lost request: the reply time-out retries it.
}

}  // namespace cellctl::scu

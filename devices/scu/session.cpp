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
std::uint8_t fnc(int function) {
  return static_cast<std::uint8_t>(function - 1);
}
// Actuator status 2 of A1..A6 (RG group): bit 0 = initialised. It is not in the cyclic object (which
// carries status 1), so it is read by itself: after the first refresh and then this often.
constexpr std::uint16_t kStatus2Group = 0x00E0;
constexpr auto kStatus2Period = std::chrono::seconds(2);
// What read_link takes from the link at a time: less than a reply, so that the reply stream (two
// replies) always takes a whole chunk beside the part of a reply it may hold.
constexpr std::size_t kReadChunk = 256;
static_assert(kReadChunk < kMaxReplyTelegram);
}  // namespace

template <class... Args>
void Session::fault(fmt::format_string<Args...> format, Args&&... args) {
  enter_fault(format, std::forward<Args>(args)...);
  urgent_.clear();
  normal_.clear();
  in_flight_.reset();
  replies_.expect_nothing();
  keepalive_armed_ = false;
}

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

void Session::drop_queued_moves(std::optional<std::uint8_t> function) {
  (void)normal_.remove_if([&](const Pending& p) {  // how many: no matter
    const bool move =
        p.purpose == Purpose::position || p.purpose == Purpose::speed || p.purpose == Purpose::execute;
    return move && (!function || p.function == *function);
  });
  for (std::size_t f = 0; f < kMotionFunctionCount; ++f) {
    if (function && f != *function) continue;
    if (snapshot_.functions[f].outcome == MoveOutcome::queued)
      snapshot_.functions[f].outcome = MoveOutcome::stopped_short;
  }
}

std::uint16_t Session::percent(int function, double speed_mm_s) const noexcept {
  const auto& fn = config_.functions[static_cast<std::size_t>(function - 1)];
  double full = 0.0;
  for (std::size_t a = 0; a < kActuatorCount; ++a)
    if (fn.actuators.test(a)) full = std::max(full, config_.specs[a].full_speed_mm_s);
  if (!(full > 0.0) || !std::isfinite(speed_mm_s)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::lround(100.0 * speed_mm_s / full), 1L, 100L));
}

bool Session::on_its_way(Purpose p) const noexcept {
  return (in_flight_ && in_flight_->purpose == p) ||
         urgent_.any([&](const Pending& q) { return q.purpose == p; });
}

CommandResult Session::move_to(int function, std::span<const ActuatorTarget> targets, double speed_mm_s,
                               bool soft) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  if (!(speed_mm_s > 0.0)) return {CommandStatus::bad_speed};
  if (snapshot_.emergency_stop_open) return {CommandStatus::emergency_stop_holds};
  const auto speed_percent = percent(function, speed_mm_s);
  const auto f = static_cast<std::size_t>(function - 1);
  auto& fs = snapshot_.functions[f];
  if (fs.execution_open || stop_queued_.test(f) || fs.outcome == MoveOutcome::queued)
    return {CommandStatus::function_busy};
  const auto& fn = config_.functions[f];
  std::bitset<kActuatorCount> given;
  for (const auto& t : targets) {
    if (!fn.moves(t.actuator)) return {CommandStatus::wrong_actuators};
    given.set(static_cast<std::size_t>(t.actuator - 1));
  }
  if (given != fn.actuators) return {CommandStatus::wrong_actuators};
  if (normal_.free_space() < targets.size() + 2) return {CommandStatus::queue_full};
  std::array<std::int32_t, kActuatorCount> edges{};
  for (const auto& t : targets) {
    const auto a = static_cast<std::size_t>(t.actuator - 1);
    const double e = std::round(t.mm * config_.specs[a].edges_per_mm);
    if (!std::isfinite(e) || std::abs(e) > 2e9) return {CommandStatus::target_out_of_range};
    edges[a] = static_cast<std::int32_t>(e);
  }
  // Room for every telegram was checked above: none of these pushes fails.
  for (const auto& t : targets) {
    const auto a = static_cast<std::size_t>(t.actuator - 1);
    fs.targets[a] = edges[a];
    std::array<std::uint8_t, 4> value{};
    wire::ByteWriter w(value);
    w.le(edges[a]);
    (void)enqueue(false, TransferRequest{data_id::remote_position(t.actuator), value}, Purpose::position,
                  fnc(function));
  }
  std::array<std::uint8_t, 2> speed{};
  wire::ByteWriter w(speed);
  w.le(speed_percent);
  (void)enqueue(false, TransferRequest{data_id::remote_speed(function), speed}, Purpose::speed,
                fnc(function));
  (void)enqueue(false,
                ExecuteRequest{fnc(function), static_cast<std::uint8_t>(Direction::remote_position),
                               soft ? kSoftStartStop : kFastStartStop},
                Purpose::execute, fnc(function));
  fs.targeted = given;
  fs.speed_percent = speed_percent;
  fs.outcome = MoveOutcome::queued;
  return {};
}

CommandResult Session::stop(int function, bool soft) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  const auto f = static_cast<std::size_t>(function - 1);
  drop_queued_moves(fnc(function));
  const StopRequest rs{fnc(function), soft ? kSoftStartStop : kFastStartStop};
  // Asked again while its RS still waits, the RS keeps its place (only its mode may change): a stop
  // asked again every cycle must not fall behind what was queued meanwhile, such as a re-sent F20.
  if (auto* queued = urgent_.find_if(
          [&](const Pending& p) { return p.purpose == Purpose::stop && p.function == fnc(function); })) {
    // An RS always fits its buffer (it fitted when it was queued).
    (void)encode_request(rs, queued->bytes);
    stop_queued_.set(f);
    return {};
  }
  if (!enqueue(true, rs, Purpose::stop, fnc(function))) return {CommandStatus::queue_full};
  stop_queued_.set(f);
  return {};
}

CommandResult Session::emergency_stop() {
  if (lifecycle() != link::Lifecycle::active && lifecycle() != link::Lifecycle::deactivating)
    return {CommandStatus::not_active};
  drop_queued_moves(std::nullopt);
  if (on_its_way(Purpose::emergency_stop)) return {};  // one F20 until the SCU has answered it
  Pending p;
  const ExecuteRequest f20{kEmergencyStopFnc, kUnusedParam, kUnusedParam};
  (void)encode_request(f20, p.bytes);  // an RE always fits its buffer
  p.shape = reply_shape(f20);
  p.purpose = Purpose::emergency_stop;
  // The first F20 goes ahead of everything. One asked for again after the SCU refused it waits behind
  // the stops queued meanwhile: an SCU that keeps refusing F20 must not starve each axis's own stop.
  const bool queued = f20_refused_ ? urgent_.push_back(p) : urgent_.push_front(p);
  return {queued ? CommandStatus::taken : CommandStatus::queue_full};
}

CommandResult Session::release_emergency_stop() {
  if (!accepting()) return {CommandStatus::not_active};
  if (!snapshot_.emergency_stop_open) return {CommandStatus::no_emergency_stop};
  // Asked every cycle until the SCU has answered: one RS goes out, not one per cycle.
  if (on_its_way(Purpose::release_emergency)) return {};
  if (!enqueue(true, StopRequest{kEmergencyStopFnc, kUnusedParam}, Purpose::release_emergency))
    return {CommandStatus::queue_full};
  return {};
}

CommandResult Session::set_speed(int function, double speed_mm_s) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  if (!(speed_mm_s > 0.0)) return {CommandStatus::bad_speed};
  const auto speed_percent = percent(function, speed_mm_s);
  if (snapshot_.functions[static_cast<std::size_t>(function - 1)].speed_percent == speed_percent) return {};
  std::array<std::uint8_t, 2> speed{};
  wire::ByteWriter w(speed);
  w.le(speed_percent);
  if (!enqueue(false, TransferRequest{data_id::remote_speed(function), speed}, Purpose::speed, fnc(function)))
    return {CommandStatus::queue_full};
  snapshot_.functions[static_cast<std::size_t>(function - 1)].speed_percent = speed_percent;
  return {};
}

CommandResult Session::read(std::uint16_t data_id) {
  if (!accepting()) return {CommandStatus::not_active};
  if (value_size(data_id) == 0 || value_size(data_id) > kMaxReplyData)
    return {CommandStatus::unknown_data_id};
  if (!enqueue(false, GetRequest{data_id}, Purpose::read, 0, data_id)) return {CommandStatus::queue_full};
  return {};
}

}  // namespace cellctl::scu

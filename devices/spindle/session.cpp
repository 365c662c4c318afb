#include "spindle/session.hpp"

#include <fmt/format.h>

#include <cmath>

#include "link/clock.hpp"
#include "link/fault_reason.hpp"
#include "spindle/fault_numbers.hpp"

namespace cellctl::spindle {
namespace {

using link::assign_formatted;

std::string_view name_of(MsgId id) noexcept {
  switch (id) {
    case MsgId::set_basic:
      return "SET Grundparameter (0x10)";
    case MsgId::set_start:
      return "SET Startparameter (0x18)";
    case MsgId::cmd_start:
      return "CMD System Start (0xA0)";
    case MsgId::cmd_stop:
      return "CMD System Stopp (0xA1)";
    case MsgId::cmd_reset:
      return "CMD System Reset (0xA2)";
    case MsgId::res_status:
      return "status values (0x59)";
    case MsgId::res_ident:
      return "identification (0x5A)";
    case MsgId::res_statusout:
      return "statusout (0x60)";
    default:
      return "message";
  }
}

constexpr bool representable_hz(double hz) noexcept {
  return std::isfinite(hz) && hz >= 0.0 && hz <= 65535.0;
}

}  // namespace

Session::Session(link::Link& link, const SessionConfig& config)
    : link_(link), config_(config), link_name_(link.describe()) {
  snapshot_.start_refused_reason.reserve(link::kFaultReasonCapacity);
  // The converter has no communication watchdog: should the process die of a fatal signal, the port
  // gets CMD System Stopp (link/crash_stop.hpp), or a crashed controller would leave the spindle turning.
  link_.arm_crash_stop(make(Command{MsgId::cmd_stop}).frame.view());
}

Session::Outgoing Session::make(const Message& m) {
  Outgoing o;
  o.frame.resize(Codec::encode(m, o.frame.storage()));
  o.sent_id = id_of(m);
  if (const auto* request = std::get_if<Request>(&m)) {
    o.answer_id = request->wanted;
  } else {
    o.answer_id = o.sent_id;
    o.command = true;
  }
  return o;
}

bool Session::enqueue(const Message& m) {
  if (queued_ == kQueueCapacity) return false;
  queue_[queued_++] = make(m);
  return true;
}

template <class... Args>
void Session::fault(fmt::format_string<Args...> format, Args&&... args) {
  enter_fault(format, std::forward<Args>(args)...);
  queued_ = 0;
  in_flight_.reset();
  watching_start_ = false;
}

void Session::activate(link::TimePoint now) {
  enter(link::Lifecycle::activating, now);
  queued_ = 0;
  in_flight_.reset();
  tx_.clear();
  decoder_.reset();
  snapshot_ = Snapshot{};
  snapshot_.start_refused_reason.reserve(link::kFaultReasonCapacity);
  activated_at_ = now;
  status_at_.reset();
  values_at_.reset();
  at_speed_since_.reset();
  next_status_at_ = next_values_at_ = now;
  stop_acked_at_.reset();
  start_parameters_sent_ = false;  // the converter may have been switched off and on in between
  watching_start_ = false;
}

void Session::deactivate(link::TimePoint) {
  if (quiet()) return;
  enter(link::Lifecycle::deactivating);
  stop_acked_at_.reset();
  (void)stop();  // taken: the session is deactivating, and a stop empties the queue first
}

bool Session::start(double frequency_hz, Direction direction) {
  if (lifecycle() != link::Lifecycle::active || !representable_hz(frequency_hz) ||
      direction == Direction::digital_input)
    return false;
  const bool send_parameters =
      config_.set_start_parameters && (!start_parameters_sent_ || sent_direction_ != direction);
  if (kQueueCapacity - queued_ < (send_parameters ? 3u : 2u)) return false;
  // Room for every command was checked above: none of these pushes fails.
  if (send_parameters) {
    (void)enqueue(SetStart{Source::sycodrive, Source::sycodrive, direction});
    start_parameters_sent_ = true;
    sent_direction_ = direction;
  }
  (void)enqueue(SetBasic{static_cast<std::uint16_t>(std::lround(frequency_hz)), SpeedUnit::hz});
  (void)enqueue(Command{MsgId::cmd_start});
  snapshot_.run_requested = true;
  snapshot_.requested_frequency_hz = frequency_hz;
  snapshot_.direction = direction;
  snapshot_.start_refused = false;
  snapshot_.start_refused_reason.clear();
  return true;
}

bool Session::set_frequency(double frequency_hz) {
  if (lifecycle() != link::Lifecycle::active || !representable_hz(frequency_hz)) return false;
  if (!enqueue(SetBasic{static_cast<std::uint16_t>(std::lround(frequency_hz)), SpeedUnit::hz})) return false;
  snapshot_.requested_frequency_hz = frequency_hz;
  return true;
}

bool Session::stop() {
  if (lifecycle() != link::Lifecycle::active && lifecycle() != link::Lifecycle::deactivating) return false;
  // Nothing queued may run after a stop: drop it all and put the stop first.
  queued_ = 0;
  watching_start_ = false;
  snapshot_.run_requested = false;
  return enqueue(Command{MsgId::cmd_stop});
}

bool Session::reset() {
  if (lifecycle() != link::Lifecycle::active) return false;
  return enqueue(Command{MsgId::cmd_reset});
}

bool Session::commands_pending() const noexcept {
  return queued_ > 0 || (in_flight_ && in_flight_->command);
}

void Session::receive(link::TimePoint now) {
  if (quiet()) return;
  snapshot_.status_age = now - status_at_.value_or(activated_at_);
  snapshot_.values_age = now - values_at_.value_or(activated_at_);
  read_replies(now);
  check_in_flight(now);
  if (lifecycle() == link::Lifecycle::fault) return;
  if (silent_for(now) > config_.link_fault_after) {
    fault("spindle converter on {} silent for {:.0f} ms (limit {:.0f} ms)", link_name_,
          link::to_milliseconds(silent_for(now)), link::to_milliseconds(config_.link_fault_after));
    return;
  }
  // Closed only once the stop is acknowledged and a statusout asked for after it reports STILLSTAND:
  // the converter has no watchdog of its own (the manual names none) and keeps turning without us.
  if (lifecycle() == link::Lifecycle::deactivating && !in_flight_ && queued_ == 0 && stop_acked_at_ &&
      status_at_ && *status_at_ > *stop_acked_at_ && snapshot_.at_rest)
    enter(link::Lifecycle::inactive);
}

void Session::transmit(link::TimePoint now) {
  if (quiet()) return;
  send_next(now);
  if (!tx_.empty()) {
    std::array<std::uint8_t, 2 * kMaxFrameLength> chunk{};
    const std::size_t n = std::min(tx_.size(), chunk.size());
    for (std::size_t i = 0; i < n; ++i) chunk[i] = tx_[i];
    const auto r = link_.write(std::span(chunk).first(n));
    if (r.ok()) tx_.drop(r.count);
  }
}

void Session::read_replies(link::TimePoint now) {
  std::array<std::uint8_t, 128> buffer{};
  for (;;) {
    const auto r = link_.read(buffer);
    if (!r.ok()) {
      fault("spindle link {} {}", link_name_, r.status == link::IoStatus::closed ? "closed" : "failed");
      return;
    }
    if (r.count == 0) return;
    for (std::size_t i = 0; i < r.count; ++i) {
      const auto d = decoder_.push(buffer[i]);
      if (!d) continue;
      if (d->ok()) {
        on_reply(now, d->message);
      } else {
        ++health_.bad_frames;  // the request in flight times out and is repeated
      }
    }
  }
}

void Session::on_reply(link::TimePoint now, const Message& m) {
  const auto* ack = std::get_if<Ack>(&m);
  const MsgId answer = ack ? ack->acknowledged : id_of(m);
  if (!in_flight_ || in_flight_->answer_id != answer || (ack != nullptr) != in_flight_->command) {
    ++health_.bad_frames;  // a late answer to a request already given up on, or a stray frame
    return;
  }
  health_.record_reply(sent_at_, now);
  if (const auto* s = std::get_if<StatusOut>(&m)) {
    on_statusout(*s);
    status_at_ = now;
    snapshot_.status_age = link::Duration::zero();
    if (!s->at_speed())
      at_speed_since_.reset();
    else if (!at_speed_since_)
      at_speed_since_ = now;
    if (!at_speed_since_) snapshot_.settled = false;
  }
  if (const auto* v = std::get_if<StatusValues>(&m)) {
    on_values(*v);
    values_at_ = now;
    snapshot_.values_age = link::Duration::zero();
    // Asked for after at-speed was seen, and at speed still: the reading is of the settled motor.
    snapshot_.settled = at_speed_since_ && sent_at_ >= *at_speed_since_;
  }
  if (const auto* id = std::get_if<Identification>(&m)) {
    snapshot_.identification = *id;
    if (lifecycle() == link::Lifecycle::activating) enter(link::Lifecycle::active);
  }
  if (ack && ack->acknowledged == MsgId::cmd_start) watching_start_ = true;
  if (ack && ack->acknowledged == MsgId::cmd_stop) stop_acked_at_ = now;
  in_flight_.reset();
}

void Session::on_statusout(const StatusOut& s) {
  snapshot_.status_valid = true;
  snapshot_.at_speed = s.at_speed();
  snapshot_.at_rest = s.at_rest();
  snapshot_.state = s.state;
  snapshot_.error_number = s.error_number;
  snapshot_.current_limit = s.current_limit();
  snapshot_.motor_over_temperature = s.over_temperature();
  snapshot_.motor_code = s.motor_code;
  if (!watching_start_) return;
  // The first statusout after the start's ACK: running, or at rest with the converter saying why not.
  watching_start_ = false;
  if (s.at_rest() && s.state != DeviceState::none) {
    const auto meaning = explain_fault_number(s.error_number);
    snapshot_.start_refused = true;
    assign_formatted(snapshot_.start_refused_reason,
                     "converter acknowledged the start but stays at rest: {} {}{}{}",
                     s.state == DeviceState::fault ? "fault" : "warning", s.error_number,
                     meaning.empty() ? "" : " — ", meaning);
  }
}

void Session::on_values(const StatusValues& v) {
  snapshot_.values_valid = true;
  snapshot_.set_frequency_hz = v.set_frequency_hz;
  snapshot_.actual_frequency_hz = v.actual_frequency_hz;
  snapshot_.peak_current_a = v.peak_current_a();
  snapshot_.motor_current_a = v.motor_current_a();
  snapshot_.power_w = v.power_w();
  snapshot_.motor_voltage_v = v.motor_voltage_v();
  snapshot_.dc_link_voltage_v = v.dc_link_voltage_v();
  snapshot_.motor_code = v.motor_code;
  snapshot_.converter_hours = v.converter_hours;
  snapshot_.motor_hours = v.motor_hours;
}

void Session::check_in_flight(link::TimePoint now) {
  if (!in_flight_ || lifecycle() == link::Lifecycle::fault || now - sent_at_ < config_.reply_timeout) return;
  ++health_.timeouts;
  if (tries_ <= config_.retries) {
    ++health_.retries;
    send(now, *in_flight_);
    return;
  }
  if (in_flight_->command) {
    // An unconfirmed SET or CMD leaves the converter's state unknown: that is a fault, not a shrug.
    fault("spindle converter on {} did not acknowledge {} after {} tries", link_name_,
          name_of(in_flight_->sent_id), tries_);
    return;
  }
  in_flight_.reset();  // a poll: the next one is due soon enough; silence is judged by link_fault_after
}

void Session::send_next(link::TimePoint now) {
  if (in_flight_) return;
  if (queued_ > 0) {
    const Outgoing next = queue_[0];
    for (std::size_t i = 1; i < queued_; ++i) queue_[i - 1] = queue_[i];
    --queued_;
    tries_ = 0;
    in_flight_ = next;
    send(now, next);
    return;
  }
  std::optional<MsgId> wanted;
  if (lifecycle() == link::Lifecycle::deactivating) {
    // Stopping: statusout only, until it reports the motor at rest.
    if (now >= next_status_at_) {
      wanted = MsgId::res_statusout;
      next_status_at_ = now + config_.status_poll;
    }
  } else if (!snapshot_.identification) {
    wanted = MsgId::res_ident;
  } else if (now >= next_status_at_) {
    wanted = MsgId::res_statusout;
    next_status_at_ = now + config_.status_poll;
  } else if (now >= next_values_at_) {
    wanted = MsgId::res_status;
    next_values_at_ = now + config_.values_poll;
  }
  if (!wanted) return;
  tries_ = 0;
  in_flight_ = make(Request{*wanted});
  send(now, *in_flight_);
}

void Session::send(link::TimePoint now, const Outgoing& o) {
  ++tries_;
  sent_at_ = now;
  // Fits: one request at a time, and the one before left the queue before its reply came (a frame cut
  // short all the same is retried as a lost request after the reply time-out).
  (void)tx_.push(o.frame.view());
}

}  // namespace cellctl::spindle

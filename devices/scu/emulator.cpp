#include "scu/emulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scu/data_list.hpp"
#include "wire/byte_reader.hpp"

namespace cellctl::scu {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
// Written out for clang 14 (the fuzz preset), which does not yet deduce aggregates' arguments.
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

// The plant is integrated in steps of at most this, whatever the poll rate, so ramps stay accurate.
constexpr link::Duration kMaxPlantStep = std::chrono::milliseconds(1);

// User positions structure (0x2001..): for each of 4 users Memory 1..4, Intermediate In/Out, then the
// virtual limits. The emulator's defaults are fractions of the stroke, the same for every user.
constexpr std::array<double, 6> kUserPositionFractions = {0.2, 0.4, 0.6, 0.8, 0.1, 0.9};

std::uint16_t percent(double part, double whole) noexcept {
  if (whole <= 0.0) return 0;
  return static_cast<std::uint16_t>(std::lround(std::clamp(part / whole, 0.0, 1.0) * 100.0));
}

}  // namespace

Emulator::Emulator(link::Link& link, const EmulatorConfig& config) : link_(link), config_(config) {
  validate(config_);
  actuators_.reserve(kActuatorCount);
  for (const auto& a : config_.actuators) actuators_.emplace_back(a.physics);
  for (auto& obj : cyclic_objects_) obj.fill(kUnusedDataId);
  remote_speed_.fill(config_.default_speed_percent);
  owner_.fill(-1);
  initialised_ = config_.initialised;
  // Remote position default: Memory 1 of user 1.
  for (std::size_t a = 0; a < remote_position_.size(); ++a) {
    const auto& act = config_.actuators[a];
    remote_position_[a] = static_cast<std::int32_t>(
        std::lround(kUserPositionFractions[0] * act.physics.stroke_mm * act.edges_per_mm));
  }
}

void Emulator::power_cycle() {
  stop_all(false);
  initialised_ = {};  // lost whatever the emulator started with (EmulatorConfig::initialised)
  remote_open_ = rc_seen_ = lapsed_ = false;
  running_ = {};
  owner_.fill(-1);
  emergency_stop_ = false;
  remote_speed_.fill(config_.default_speed_percent);
}

plant::Actuator& Emulator::actuator(int a) {
  if (!present(a)) throw std::out_of_range("scu emulator: no actuator " + std::to_string(a));
  return actuators_[index(a)];
}

const plant::Actuator& Emulator::actuator(int a) const {
  if (!present(a)) throw std::out_of_range("scu emulator: no actuator " + std::to_string(a));
  return actuators_[index(a)];
}

std::int32_t Emulator::position_edges(int a) const {
  if (!present(a)) return 0;
  return static_cast<std::int32_t>(
      std::lround(actuators_[index(a)].position_mm() * config_.actuators[index(a)].edges_per_mm));
}

Status1 Emulator::status1(int a) const {
  if (!present(a)) return {};
  const auto& p = actuators_[index(a)];
  Status1 s;
  s.present = true;
  s.limit_signal = p.at_in_limit() || p.at_out_limit();
  // Motion active follows the plant: a commanded motion that is not stalled (below the minimum speed
  // or jammed, the motor does not turn and the SCU does not report motion).
  s.motion_active = p.active() && !p.stalled();
  s.in_position = p.at_in_limit();
  s.out_position = p.at_out_limit();
  s.stroke_recorded = true;
  return s;
}

void Emulator::poll(link::TimePoint now) {
  if (last_poll_ && now > *last_poll_) step_plant(now - *last_poll_);
  if (!last_poll_ || now > *last_poll_) last_poll_ = now;
  // What has arrived is read before the watchdog is judged: when this thread was kept off the CPU,
  // an RC that came in time must not count as missing.
  receive(now);
  run_watchdog(now);
  flush(now);
}

void Emulator::step_plant(link::Duration dt) {
  while (dt > link::Duration::zero()) {
    const auto h = std::min(dt, kMaxPlantStep);
    for (std::size_t a = 0; a < actuators_.size(); ++a) {
      if (!config_.actuators[a].present) continue;
      const double before = actuators_[a].position_mm();
      actuators_[a].step(h);
      stroke_edges_[a] += std::abs(actuators_[a].position_mm() - before) * config_.actuators[a].edges_per_mm;
      // Our reading of the silent manual: an actuator is initialised by a run into its retracted end.
      if (actuators_[a].at_in_limit() && before > 0.0) initialised_[a] = true;
      if (!actuators_[a].active()) owner_[a] = -1;
    }
    dt -= h;
  }
}

void Emulator::run_watchdog(link::TimePoint now) {
  if (!remote_open_ || lapsed_ || now - last_rc_at_ <= kWatchdogPeriod) return;
  lapsed_ = true;
  raise_error(error_bit::kRemoteTimeout);
  // Safety_ID 0 and 1 terminate all movements, 2 only the remote ones; every motion of the emulator
  // is a remote one, so all three stop everything.
  stop_all(false);
}

void Emulator::receive(link::TimePoint now) {
  // A request's length at a time: beside the part of a request it may hold, the stream (two requests)
  // takes all of it, and the events are drained before the next read.
  std::array<std::uint8_t, kMaxRequestTelegram> buf{};
  if (requests_.expire(now) > 0) ++discarded_partials_;
  for (;;) {
    const auto r = link_.read(buf);
    if (!r.ok() || r.count == 0) break;
    (void)requests_.feed(std::span(buf).first(r.count), now);  // all of it (see buf)
    for (auto e = requests_.next(); e.kind != RequestStream::Event::Kind::need_more; e = requests_.next()) {
      if (e.kind == RequestStream::Event::Kind::request) {
        answer(e.request, now);
        continue;
      }
      switch (e.error) {
        case DecodeError::bad_crc:
          answer_error(e.command_byte, Status::checksum_error, now);
          break;
        case DecodeError::bad_length:
          answer_error(e.command_byte, Status::parameter_count_error, now);
          break;
        case DecodeError::unknown_command:
          answer_error(e.command_byte, Status::invalid_command, now);
          break;
        default:
          break;  // garbage before a telegram gets no answer: there is nobody to answer
      }
    }
  }
}

Status Emulator::remote_permission() const noexcept {
  if (!remote_open_ || !rc_seen_) return Status::permission_error;  // RO, then RC before anything else
  if (lapsed_ && safety_id_ == 0) return Status::permission_error;  // after a lapse only RC, RA, RO
  return Status::ack;
}

void Emulator::answer(const Request& request, link::TimePoint now) {
  if (refuse_count_ > 0 && (!refuse_only_ || *refuse_only_ == command_of(request))) {
    --refuse_count_;
    send(Reply{command_of(request), refuse_status_, false, {}}, now);
    return;
  }
  wire::ByteWriter data(reply_data_);
  Reply reply;
  reply.command = command_of(request);
  reply.has_data = reply_shape(request).has_data;
  reply.status = std::visit(Overloaded{
                                [&](const OpenRequest& r) { return handle(r, now); },
                                [&](const AbortRequest& r) { return handle(r, now); },
                                [&](const CyclicRequest& r) { return handle(r, now, data); },
                                [&](const GetRequest& r) { return handle(r, data); },
                                [&](const TransferRequest& r) { return handle(r); },
                                [&](const ExecuteRequest& r) { return handle(r); },
                                [&](const StopRequest& r) { return handle(r); },
                            },
                            request);
  reply.data = data.written();
  send(reply, now);
}

void Emulator::answer_error(std::uint8_t command_byte, Status s, link::TimePoint now) {
  send(Reply{static_cast<Command>(command_byte), s, false, {}}, now);
}

Status Emulator::handle(const OpenRequest& r, link::TimePoint now) {
  if (r.safety_id > 2) return Status::parameter_data_error;
  remote_open_ = true;
  rc_seen_ = false;
  lapsed_ = false;
  safety_id_ = r.safety_id;
  last_rc_at_ = now;  // the watchdog runs from RO: the first RC is due within 500 ms as well
  error_codes_[0] &= ~ErrorWord::mask(error_bit::kRemoteTimeout);
  return Status::ack;
}

Status Emulator::handle(const AbortRequest&, link::TimePoint) {
  if (remote_open_) stop_all(true);  // back to normal mode: nothing remote keeps moving
  remote_open_ = false;
  rc_seen_ = false;
  running_.fill(false);
  return Status::ack;
}

Status Emulator::handle(const CyclicRequest& r, link::TimePoint now, wire::ByteWriter& out) {
  if (!remote_open_) return Status::permission_error;
  if (r.index != kNoCyclicObject && r.index >= kCyclicObjectCount) return Status::parameter_data_error;
  if (r.index == kNoCyclicObject && !r.write_data.empty()) return Status::parameter_count_error;
  if (rc_seen_) max_rc_gap_ = std::max(max_rc_gap_, now - last_rc_at_);
  rc_seen_ = true;
  last_rc_at_ = now;
  ++rc_count_;
  if (lapsed_ && safety_id_ != 0) lapsed_ = false;  // Safety_ID 1/2: RC resumes remote mode
  if (r.index == kNoCyclicObject) return Status::ack;

  const auto& obj = cyclic_objects_[r.index];
  // Write data: the concatenated values of the first six IDs, checked whole before anything changes.
  std::size_t expected = 0;
  for (std::size_t i = 0; i < 6; ++i)
    if (obj[i] != kUnusedDataId) expected += value_size(obj[i]);
  if (r.write_data.size() != expected) return Status::parameter_count_error;
  std::size_t at = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    if (obj[i] == kUnusedDataId) continue;
    const auto n = value_size(obj[i]);
    if (const auto s = check_write(obj[i], r.write_data.subspan(at, n)); s != Status::ack) return s;
    at += n;
  }
  at = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    if (obj[i] == kUnusedDataId) continue;
    const auto n = value_size(obj[i]);
    apply_write(obj[i], r.write_data.subspan(at, n));
    at += n;
  }
  for (std::size_t i = 6; i < 12; ++i)
    if (obj[i] != kUnusedDataId && !read_value(obj[i], out)) return Status::parameter_data_error;
  return out.ok() ? Status::ack : Status::parameter_data_error;
}

Status Emulator::handle(const GetRequest& r, wire::ByteWriter& out) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  return read_value(r.data_id, out) && out.ok() ? Status::ack : Status::parameter_data_error;
}

Status Emulator::handle(const TransferRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  const auto s = check_write(r.data_id, r.value);
  if (s == Status::ack) apply_write(r.data_id, r.value);
  return s;
}

Status Emulator::handle(const ExecuteRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  if (r.function < kMotionFunctionCount) {
    const auto& fn = config_.functions[r.function];
    if (!fn.defined || r.direction > static_cast<std::uint8_t>(Direction::remote_position))
      return Status::parameter_data_error;
    if (r.start_stop != kFastStartStop && r.start_stop != kSoftStartStop && r.start_stop != kUnusedParam)
      return Status::parameter_data_error;
    if (emergency_stop_) return Status::permission_error;  // F20 holds until its RS
    if (config_.refuses_execute_while_moving) {
      for (std::size_t a = 0; a < actuators_.size(); ++a)
        if (fn.moves(static_cast<int>(a) + 1) && actuators_[a].moving()) return Status::permission_error;
    }
    running_[r.function] = true;
    const auto d = static_cast<Direction>(r.direction);
    if (d != Direction::none) start_function(r.function, d, r.start_stop != kFastStartStop);
    return Status::ack;
  }
  switch (r.function) {
    case kEmergencyStopFnc:
      emergency_stop_ = true;
      stop_all(false);
      return Status::ack;
    case kBuzzerFnc:
      buzzer_ = 1;
      return Status::ack;
    case kBinaryOutput1Fnc:
      outputs_ |= 0x01;
      return Status::ack;
    case kBinaryOutput2Fnc:
      outputs_ |= 0x02;
      return Status::ack;
    case kLed1Fnc:
      hand_switch_leds_ |= 0x01;
      return Status::ack;
    case kLed2Fnc:
      hand_switch_leds_ |= 0x02;
      return Status::ack;
    default:
      return Status::parameter_data_error;
  }
}

Status Emulator::handle(const StopRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  if (r.mode != kFastStartStop && r.mode != kSoftStartStop && r.mode != kUnusedParam)
    return Status::parameter_data_error;
  if (r.function < kMotionFunctionCount) {
    if (!config_.functions[r.function].defined) return Status::parameter_data_error;
    stop_function(r.function, r.mode != kFastStartStop);
    running_[r.function] = false;
    return Status::ack;
  }
  switch (r.function) {
    case kEmergencyStopFnc:
      emergency_stop_ = false;
      return Status::ack;
    case kBuzzerFnc:
      buzzer_ = 0;
      return Status::ack;
    case kBinaryOutput1Fnc:
      outputs_ &= 0xFE;
      return Status::ack;
    case kBinaryOutput2Fnc:
      outputs_ &= 0xFD;
      return Status::ack;
    case kLed1Fnc:
      hand_switch_leds_ &= 0xFE;
      return Status::ack;
    case kLed2Fnc:
      hand_switch_leds_ &= 0xFD;
      return Status::ack;
    default:
      return Status::parameter_data_error;
  }
}

double Emulator::target_mm(std::size_t a, Direction d) const {
  const double stroke = config_.actuators[a].physics.stroke_mm;
  switch (d) {
    case Direction::none:
      return actuators_[a].position_mm();
    case Direction::in:
      return 0.0;
    case Direction::out:
      return stroke;
    case Direction::memory1:
    case Direction::memory2:
    case Direction::memory3:
    case Direction::memory4:
    case Direction::intermediate_in:
    case Direction::intermediate_out:
      return kUserPositionFractions[static_cast<std::size_t>(d) -
                                    static_cast<std::size_t>(Direction::memory1)] *
             stroke;
    case Direction::remote_position:
      return remote_position_[a] / config_.actuators[a].edges_per_mm;
  }
  return actuators_[a].position_mm();
}

void Emulator::start_function(std::size_t f, Direction d, bool soft) {
  const auto& fn = config_.functions[f];
  // Bits 14..21 are reset with the next motion.
  for (int bit = error_bit::kTotalCurrent; bit <= error_bit::kPositionDifference; ++bit)
    error_codes_[0] &= ~ErrorWord::mask(bit);
  // A synchronized run goes at the pace of the slowest actuator, so that all keep together.
  double max_speed = 1e300;
  for (int a = 1; a <= kActuatorCount; ++a)
    if (fn.moves(a)) max_speed = std::min(max_speed, config_.actuators[index(a)].physics.max_speed_mm_s);
  for (int a = 1; a <= kActuatorCount; ++a) {
    if (!fn.moves(a)) continue;
    const auto i = index(a);
    const double pct = remote_speed_[f] / 100.0;
    const double speed = pct * (fn.synchronized ? max_speed : config_.actuators[i].physics.max_speed_mm_s);
    const double target = target_mm(i, d);
    (target >= actuators_[i].position_mm() ? relay_out_[i] : relay_in_[i]) += 1;
    actuators_[i].move_to(target, speed, soft);
    owner_[i] = static_cast<int>(f);
    if (lasting_fault_[i]) inject_actuator_fault(a);
  }
}

void Emulator::stop_function(std::size_t f, bool soft) {
  for (std::size_t a = 0; a < actuators_.size(); ++a) {
    if (owner_[a] != static_cast<int>(f)) continue;
    actuators_[a].stop(soft);
  }
}

void Emulator::stop_all(bool soft) {
  for (std::size_t a = 0; a < actuators_.size(); ++a)
    if (config_.actuators[a].present) actuators_[a].stop(soft);
}

void Emulator::raise_error(int bit) {
  auto& latest = error_codes_[0];
  if ((latest & ErrorWord::mask(bit)) != 0) return;
  // A new error: the word as it was moves into the history (0x00D2..D5) before the bit is added.
  if (latest != 0) {
    std::copy_backward(error_codes_.begin(), error_codes_.end() - 1, error_codes_.end());
  }
  latest |= ErrorWord::mask(bit);
}

void Emulator::inject_actuator_fault(int a) {
  if (!present(a)) throw std::out_of_range("scu emulator: no actuator " + std::to_string(a));
  raise_error(error_bit::actuator_fault(a));
  ++actuator_errors_[index(a)];
  actuators_[index(a)].stop(false);
}

void Emulator::set_actuator_fault(int a, bool on) {
  if (!present(a)) throw std::out_of_range("scu emulator: no actuator " + std::to_string(a));
  lasting_fault_[index(a)] = on;
  if (on) inject_actuator_fault(a);
}

void Emulator::inject_over_current() {
  raise_error(error_bit::kTotalCurrent);
  ++over_current_count_;
  stop_all(false);
}

void Emulator::inject_position_difference(int function) {
  if (function < 1 || function > kMotionFunctionCount)
    throw std::out_of_range("scu emulator: no function F" + std::to_string(function));
  raise_error(error_bit::kPositionDifference);
  stop_function(index(function), false);
}

bool Emulator::read_value(std::uint16_t id, wire::ByteWriter& out) const {
  const auto elements = elements_of(id);
  if (elements.empty()) return false;
  for (const auto& e : elements) read_element(e.id, out);
  return true;
}

void Emulator::read_element(std::uint16_t id, wire::ByteWriter& out) const {
  const int low = id & 0x0F;  // actuator / function / history number inside a block
  const auto a = static_cast<std::size_t>(std::clamp(low, 1, kActuatorCount) - 1);
  const bool is_present = low >= 1 && low <= kActuatorCount && config_.actuators[a].present;
  const auto& phys = config_.actuators[a].physics;
  const auto string_of = [&](const std::string& s, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) out.u8(i < s.size() ? static_cast<std::uint8_t>(s[i]) : 0);
  };
  const auto current = [&]() -> std::uint16_t {  // 0.1 A: 2 A idle draw of a running motor, + load with speed
    if (!is_present || !actuators_[a].moving()) return 0;
    return static_cast<std::uint16_t>(
        20 + percent(std::abs(actuators_[a].velocity_mm_s()), phys.max_speed_mm_s) / 2);
  };
  switch (id & 0xFFF0) {
    case 0x0000:
      string_of(id == data_id::kFirmwareInfo ? config_.firmware : config_.configuration, value_size(id));
      return;
    case 0x0010:
      out.le(position_edges(low));
      return;
    case 0x0030:
      out.le(std::uint16_t{0});
      return;
    case 0x0060:
      out.le(is_present ? relay_in_[a] : 0u);
      return;
    case 0x0070:
      out.le(is_present ? relay_out_[a] : 0u);
      return;
    case 0x0080:
      out.le(id == 0x008F ? over_current_count_ : is_present ? actuator_errors_[a] : 0u);
      return;
    case 0x0090:
      out.le(is_present ? static_cast<std::uint32_t>(stroke_edges_[a]) : 0u);
      return;
    case 0x00A0:
      out.le(current());
      return;
    case 0x00B0: {
      std::uint16_t total = 0;
      for (auto m : max_current_) total = std::max(total, m);
      out.le(id == 0x00BF ? total : std::max(max_current_[a], current()));
      return;
    }
    case 0x00C0:
      if (id == 0x00C0)
        out.u8(40);
      else
        out.le(std::uint32_t{0});
      return;
    case 0x00D0:
      out.le(error_codes_[static_cast<std::size_t>(low - 1)]);
      return;
    case 0x00E0:
      out.u8(Status2{is_present && initialised_[a], is_present, is_present}.to_byte());
      return;
    case 0x00F0:
      out.le(is_present ? percent(std::abs(actuators_[a].velocity_mm_s()), phys.max_speed_mm_s)
                        : std::uint16_t{0});
      return;
    case 0x0160:
      if (id == 0x0166)
        out.u8(1);  // user 1
      else if (id == 0x0165)
        out.u8(0);  // no locking box
      else
        out.le(std::uint16_t{0});  // nothing locked, no battery
      return;
    case 0x0170:
      out.u8(status1(low).to_byte());
      return;
    case 0x1010:
      out.le_float(is_present ? static_cast<float>(1.0 / config_.actuators[a].edges_per_mm) : 0.0f);
      return;
    case 0x2000: {
      const double scale = is_present ? phys.stroke_mm * config_.actuators[a].edges_per_mm : 0.0;
      for (int user = 0; user < 4; ++user)
        for (double f : kUserPositionFractions) out.le(static_cast<std::int32_t>(std::lround(f * scale)));
      out.le(std::int32_t{0});
      out.le(static_cast<std::int32_t>(std::lround(scale)));
      return;
    }
    case 0x3000:
      for (auto v : cyclic_objects_[static_cast<std::size_t>(low - 1)]) out.le(v);
      return;
    case 0x3010:
      out.le(remote_speed_[static_cast<std::size_t>(low - 1)]);
      return;
    case 0x3020:
      out.le(remote_position_[a]);
      return;
    default:
      break;
  }
  switch (id) {
    case 0x0020:
      out.u8(0);
      return;
    case 0x0040:
      out.le(std::uint32_t{0});
      return;
    case 0x0100:
      out.u8(0x01);
      return;  // mains connected
    case 0x0110:
      out.u8(outputs_);
      return;
    case 0x0120:
      out.u8(hand_switch_leds_);
      return;
    case 0x0130:
      out.u8(0);
      return;
    case 0x0140:
      out.u8(buzzer_);
      return;
    case 0x0150:
      out.u8(1);
      return;  // sensor supply on
    default:
      break;
  }
  for (std::size_t i = 0; i < value_size(id); ++i)
    out.u8(0);  // unreachable for listed IDs; keeps sizes right
}

Status Emulator::check_write(std::uint16_t id, std::span<const std::uint8_t> value) const {
  const auto elements = elements_of(id);
  if (elements.empty()) return Status::parameter_data_error;
  if (!is_remote_data(id)) return Status::permission_error;  // only 0x3xxx is writable
  if (value.size() != value_size(id)) return Status::parameter_count_error;
  wire::ByteReader r(value);
  for (const auto& e : elements) {
    if (e.type == DataType::cyclic_object) {
      for (std::size_t i = 0; i < 12; ++i) {
        const auto ref = r.le<std::uint16_t>();
        if (ref == kUnusedDataId) continue;
        if (value_size(ref) == 0) return Status::parameter_data_error;
        if (i < 6 && !is_remote_data(ref)) return Status::parameter_data_error;  // write IDs must be 3xxx
      }
    } else if ((e.id & 0xFFF0) == 0x3010) {
      if (r.le<std::uint16_t>() > 100) return Status::parameter_data_error;  // speed in %
    } else {
      (void)r.bytes(size_of(e.type));  // skipped: any other value is taken as it is
    }
  }
  return Status::ack;
}

void Emulator::apply_write(std::uint16_t id, std::span<const std::uint8_t> value) {
  wire::ByteReader r(value);
  for (const auto& e : elements_of(id)) {
    const auto low = static_cast<std::size_t>((e.id & 0x0F) - 1);
    if (e.type == DataType::cyclic_object) {
      for (auto& v : cyclic_objects_[low]) v = r.le<std::uint16_t>();
    } else if ((e.id & 0xFFF0) == 0x3010) {
      remote_speed_[low] = r.le<std::uint16_t>();
      // A speed change during the motion: the SCU adjusts the speed keeping the ramp.
      const auto& fn = config_.functions[low];
      for (int a = 1; a <= kActuatorCount; ++a) {
        if (!fn.moves(a) || owner_[index(a)] != static_cast<int>(low)) continue;
        actuators_[index(a)].set_speed(remote_speed_[low] / 100.0 *
                                       config_.actuators[index(a)].physics.max_speed_mm_s);
      }
    } else if ((e.id & 0xFFF0) == 0x3020) {
      remote_position_[low] = r.le<std::int32_t>();
    }
  }
}

void Emulator::send(const Reply& reply, link::TimePoint now) {
  ++answered_;
  if (drop_replies_ > 0) {
    --drop_replies_;
    return;
  }
  if (outgoing_count_ == kOutgoing) return;  // a master that does not wait for replies loses some
  auto& slot = outgoing_[outgoing_count_];
  if (!encode_reply(reply, slot.bytes)) return;
  if (corrupt_next_) {
    corrupt_next_ = false;
    auto bytes = slot.bytes.storage();
    bytes[slot.bytes.size() - 1] ^= 0x5A;
  }
  slot.due = now + reply_delay_;
  ++outgoing_count_;
}

void Emulator::flush(link::TimePoint now) {
  while (outgoing_count_ > 0 && outgoing_[0].due <= now) {
    const auto bytes = outgoing_[0].bytes.view();
    if (bytes.size() > tx_.size() - tx_size_) break;
    std::copy(bytes.begin(), bytes.end(), tx_.begin() + static_cast<std::ptrdiff_t>(tx_size_));
    tx_size_ += bytes.size();
    std::move(outgoing_.begin() + 1, outgoing_.begin() + static_cast<std::ptrdiff_t>(outgoing_count_),
              outgoing_.begin());
    --outgoing_count_;
  }
  if (tx_size_ == 0) return;
  const auto r = link_.write(std::span(tx_).first(tx_size_));
  if (!r.ok() || r.count == 0) return;
  std::copy(tx_.begin() + static_cast<std::ptrdiff_t>(r.count),
            tx_.begin() + static_cast<std::ptrdiff_t>(tx_size_), tx_.begin());
  tx_size_ -= r.count;
}

}  // namespace cellctl::scu

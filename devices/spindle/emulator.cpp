#include "spindle/emulator.hpp"

#include <algorithm>
#include <cmath>

#include "spindle/fault_numbers.hpp"

namespace cellctl::spindle {
namespace {

// A small HF motor's electrical picture, enough for values that rise with speed and load.
constexpr double kVoltsPerHz = 0.05;         // V/f characteristic: 20 V at 400 Hz
constexpr double kNoLoadCurrentA = 0.3;      // magnetising current while energised
constexpr double kAmpsPerHz = 0.0015;        // friction and windage grow with speed
constexpr double kRunUpExtraCurrentA = 0.8;  // accelerating the rotor
constexpr double kPowerFactor = 0.9;

std::uint16_t scaled_u16(double value, double scale) noexcept {
  return static_cast<std::uint16_t>(std::clamp(std::lround(value * scale), 0L, 65535L));
}
std::uint32_t whole_hours(double seconds) noexcept {
  return static_cast<std::uint32_t>(seconds / 3600.0);
}

}  // namespace

Emulator::Emulator(link::Link& link, const EmulatorConfig& config)
    : link_(link),
      config_(config),
      motor_(plant::SpindleMotorParams{config.ramp_up_hz_s, config.ramp_down_hz_s}),
      converter_seconds_(config.converter_hours * 3600.0),
      motor_seconds_(config.motor_hours * 3600.0) {}

void Emulator::poll(link::TimePoint now) {
  std::array<std::uint8_t, 128> buffer{};
  for (;;) {
    const auto r = link_.read(buffer);
    if (!r.ok() || r.count == 0) break;
    if (silent_) continue;
    for (std::size_t i = 0; i < r.count; ++i) {
      const auto d = decoder_.push(buffer[i]);
      if (!d) continue;
      if (d->ok()) {
        ++frames_handled_;
        handle(d->message);
      } else {
        ++frames_rejected_;  // no NAK exists: the client's time-out is the answer
      }
    }
  }
  if (last_poll_ && now > *last_poll_) {
    const auto dt = now - *last_poll_;
    motor_.step(dt);
    converter_seconds_ += link::to_seconds(dt);
    if (!motor_.at_rest()) motor_seconds_ += link::to_seconds(dt);
  }
  last_poll_ = now;
  flush();
}

void Emulator::handle(const Message& m) {
  if (const auto* request = std::get_if<Request>(&m)) {
    switch (request->wanted) {
      case MsgId::res_status:
        reply(status_values());
        break;
      case MsgId::res_ident:
        reply(identification());
        break;
      default:
        reply(statusout());
        break;
    }
  } else if (const auto* basic = std::get_if<SetBasic>(&m)) {
    handle_set_basic(*basic);
    reply(Ack{MsgId::set_basic});
  } else if (const auto* start = std::get_if<SetStart>(&m)) {
    start_parameters_ = *start;
    if (running_) drive_motor();  // a new direction takes effect at once (through 0 Hz)
    reply(Ack{MsgId::set_start});
  } else if (const auto* command = std::get_if<Command>(&m)) {
    handle_command(command->id);
    reply(Ack{command->id});
  }
  // ACKs and RES frames are the converter's own messages: a client never sends them, so no answer.
}

void Emulator::handle_set_basic(const SetBasic& m) {
  if (m.frequency_hz < config_.min_hz || m.frequency_hz > config_.max_hz) {
    latch_fault(kFaultSetpointOutOfRange);  // the set-point is not taken
    return;
  }
  set_frequency_hz_ = m.frequency_hz;
  if (running_) drive_motor();
}

void Emulator::handle_command(MsgId id) {
  switch (id) {
    case MsgId::cmd_start:
      if (fault_) return;  // a latched fault must be reset first
      if (start_parameters_.start_source != Source::sycodrive ||
          start_parameters_.setpoint_source != Source::sycodrive) {
        start_refused_ = true;  // acknowledged, but the motor stays at rest (manual 5.1.2 HINWEIS)
        return;
      }
      start_refused_ = false;
      running_ = true;
      drive_motor();
      return;
    case MsgId::cmd_stop:
      running_ = false;
      start_refused_ = false;
      motor_.stop();
      return;
    default:  // reset: clears a latched fault whose cause is gone
      start_refused_ = false;
      if (!over_temperature_) fault_.reset();
      return;
  }
}

void Emulator::drive_motor() noexcept {
  // P146 = digital input: no input is wired to the emulator, which reads it as clockwise.
  motor_.run(set_frequency_hz_, start_parameters_.direction != Direction::counter_clockwise);
}

void Emulator::set_over_temperature(bool hot) noexcept {
  over_temperature_ = hot;
  if (hot) latch_fault(kFaultMotorOverTemperature);
}

void Emulator::latch_fault(std::uint8_t number) noexcept {
  if (fault_ == number) return;
  fault_ = number;
  std::copy_backward(fault_history_.begin(), fault_history_.end() - 1, fault_history_.end());
  fault_history_[0] = number;
  running_ = false;
  motor_.stop();
}

bool Emulator::accelerating() const noexcept {
  return std::abs(motor_.target_hz()) > std::abs(motor_.frequency_hz());
}

StatusOut Emulator::statusout() const noexcept {
  StatusOut s;
  if (fault_) {
    s.state = DeviceState::fault;
    s.error_number = *fault_;
  } else if (start_refused_) {
    s.state = DeviceState::warning;
    s.error_number = kWarningStartSourceNotRs232;
  } else if (current_limit_) {
    s.state = DeviceState::warning;
    s.error_number = kWarningCurrentLimit;
  }
  if (motor_.at_rest()) s.flags |= StatusOut::kAtRestFlags;
  if (running_ && set_frequency_hz_ > 0 && motor_.frequency_hz() == motor_.target_hz())
    s.flags |= StatusOut::kAtSpeedFlag;
  if (current_limit_) s.flags |= StatusOut::kCurrentLimitFlag;
  if (over_temperature_) s.flags |= StatusOut::kOverTemperatureFlag;
  s.motor_code = config_.motor_code;
  return s;
}

StatusValues Emulator::status_values() const noexcept {
  const double hz = std::abs(motor_.frequency_hz());
  double current = 0.0;
  if (!motor_.at_rest()) {
    current = kNoLoadCurrentA + kAmpsPerHz * hz + (accelerating() ? kRunUpExtraCurrentA : 0.0);
    current = current_limit_ ? config_.current_limit_a : std::min(current, config_.current_limit_a);
  }
  const double voltage = std::min(kVoltsPerHz * hz, config_.dc_link_voltage_v);
  StatusValues v;
  v.set_frequency_hz = set_frequency_hz_;
  v.peak_current_ca = scaled_u16(config_.current_limit_a, 100.0);
  v.actual_frequency_hz = scaled_u16(hz, 1.0);
  v.motor_voltage_cv = scaled_u16(voltage, 100.0);
  v.dc_link_voltage_cv = scaled_u16(config_.dc_link_voltage_v, 100.0);
  v.motor_current_ca = scaled_u16(current, 100.0);
  v.power_dw = scaled_u16(voltage * current * kPowerFactor, 10.0);
  v.motor_code = config_.motor_code;
  v.converter_hours = whole_hours(converter_seconds_);
  v.motor_hours = whole_hours(motor_seconds_);
  return v;
}

Identification Emulator::identification() const noexcept {
  Identification id;
  std::copy(fault_history_.begin(), fault_history_.end(), std::begin(id.fault_history));
  id.converter_type = config_.converter_type;
  id.firmware = config_.firmware;
  id.serial_number = config_.serial_number;
  return id;
}

void Emulator::reply(const Message& m) {
  if (drop_replies_ > 0) {
    --drop_replies_;
    return;
  }
  std::array<std::uint8_t, kMaxFrameLength> frame{};
  const std::size_t n = Codec::encode(m, frame);
  if (corrupt_next_) {
    // Another valid hex digit in the checksum's low position: well-formed, but the sum is wrong.
    frame[n - 2] = frame[n - 2] == '0' ? '1' : '0';
    corrupt_next_ = false;
  }
  // Replies the line has not taken fill the queue (1 KiB) only when nobody reads: one that does not fit
  // is cut short there, and the master, if it comes back, sees a bad frame.
  (void)tx_.push(std::span(frame).first(n));
}

void Emulator::flush() {
  std::array<std::uint8_t, 256> chunk{};
  while (!tx_.empty()) {
    const std::size_t n = std::min(tx_.size(), chunk.size());
    for (std::size_t i = 0; i < n; ++i) chunk[i] = tx_[i];
    const auto r = link_.write(std::span(chunk).first(n));
    if (!r.ok() || r.count == 0) return;
    tx_.drop(r.count);
  }
}

}  // namespace cellctl::spindle

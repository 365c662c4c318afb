#include "encoder/encoder_device.hpp"

#include <cmath>
#include <cstdlib>

namespace cellctl::encoder {
namespace {

constexpr std::uint64_t kNsPerTenthHour = 360'000'000'000ull;
constexpr std::uint64_t kOperatingTimeLimit = 876'000;  // 87600 h (4.2.9 bit 4), in 0.1 h

}  // namespace

EncoderDevice::EncoderDevice(const DeviceIdentity& identity, const NonVolatile& eeprom) noexcept
    : identity_(identity),
      eeprom_(eeprom),
      scaling_(params_, identity.physical),
      total_(std::max<std::uint64_t>(identity.physical.total(), 1)) {
  params_.code_sequence = eeprom_.code_sequence;
}

void EncoderDevice::parameterize(const EncoderParameters& p) noexcept {
  params_ = p;
  eeprom_.code_sequence = p.code_sequence;
  scaling_ = Scaling(params_, identity_.physical);
  last_output_ = 0;
  preset_ack_ = direction_ack_ = teach_in_ = false;
  teach_result_.reset();
  sampled_at_.reset();
  velocity_ = 0.0;
  velocity16_ = acceleration16_ = 0;
}

std::uint64_t EncoderDevice::coded_physical() const noexcept {
  const auto steps = static_cast<double>(identity_.physical.steps_per_revolution);
  const auto raw = static_cast<long long>(std::floor(revolutions_ * steps));
  const auto total = static_cast<long long>(total_);
  const auto wrapped = static_cast<std::uint64_t>(((raw % total) + total) % total);
  return eeprom_.code_sequence == CodeSequence::ccw ? (total_ - wrapped) % total_ : wrapped;
}

std::uint32_t EncoderDevice::position() const noexcept {
  // Teach-In runs unscaled and with an offset of 0 (4.4.2.1).
  if (teach_in_) return static_cast<std::uint32_t>(coded_physical());
  const auto range = static_cast<long long>(scaling_.range());
  const auto units = static_cast<long long>(scaling_.to_units(coded_physical()));
  return static_cast<std::uint32_t>((((units + eeprom_.offset) % range) + range) % range);
}

void EncoderDevice::sample(double revolutions, link::TimePoint now) noexcept {
  revolutions_ = revolutions;
  const double sign = eeprom_.code_sequence == CodeSequence::ccw ? -1.0 : 1.0;
  const double units = sign * revolutions * scaling_.units_per_revolution();
  if (!sampled_at_) {
    sampled_at_ = now;
    sampled_units_ = units;
    return;
  }
  const link::Duration period = sample_period(params_.time_base);
  const link::Duration elapsed = now - *sampled_at_;
  if (elapsed < period) return;
  // Units counted over one sample period (stretched polls are scaled back to the period).
  const double per_period = (units - sampled_units_) * link::to_seconds(period) / link::to_seconds(elapsed);
  const double v =
      params_.time_base == TimeBase::rpm ? per_period / scaling_.units_per_revolution() * 60.0 : per_period;
  acceleration16_ = saturate16(v - velocity_);
  velocity16_ = saturate16(v);
  velocity_ = v;
  sampled_at_ = now;
  sampled_units_ = units;
}

std::uint32_t EncoderDevice::status_word() const noexcept {
  std::uint32_t w = 0;
  if ((alarms_ & alarm::position_error) == 0) w |= bits::ready;
  if (!params_.commissioning) w |= bits::mode;
  const std::uint32_t pos = position();
  if ((params_.lower_limit_enabled && pos < params_.lower_limit) ||
      (params_.upper_limit_enabled && pos > params_.upper_limit))
    w |= bits::limit_switch;
  if (eeprom_.code_sequence == CodeSequence::ccw) w |= bits::code_sequence;
  if (teach_in_) w |= bits::teach_in_start;
  if (preset_ack_) w |= bits::preset;
  return w;
}

void EncoderDevice::on_edges(std::uint32_t out) noexcept {
  const std::uint32_t rising = out & ~last_output_;
  const std::uint32_t falling = ~out & last_output_;
  const bool with_status = has_status_bits(params_);

  if ((rising & bits::preset) != 0 && !teach_in_) {
    // 4.3.2/4.3.3: preset to the low 25 (31) bits; the value must be below the total range.
    const std::uint32_t value = out & (with_status ? bits::position25 : bits::position31);
    if (value < scaling_.range()) {
      const auto units = static_cast<std::int64_t>(scaling_.to_units(coded_physical()));
      eeprom_.offset = static_cast<std::int32_t>(static_cast<std::int64_t>(value) - units);
      preset_ack_ = with_status;
    }
  }
  if ((falling & bits::preset) != 0) preset_ack_ = false;
  if (!with_status) return;  // the manufacturer functions need the status bits and commissioning

  const bool commissioning = params_.commissioning;
  if ((rising & bits::code_sequence) != 0 && commissioning && !teach_in_) {
    eeprom_.code_sequence = (out & 1u) != 0 ? CodeSequence::ccw : CodeSequence::cw;
    params_.code_sequence = eeprom_.code_sequence;
    direction_ack_ = true;
  }
  if ((falling & bits::code_sequence) != 0) direction_ack_ = false;

  if ((rising & bits::teach_in_start) != 0 && commissioning && !teach_in_) {
    teach_in_ = true;
    teach_start_ = coded_physical();
  }
  if ((rising & bits::teach_in_end) != 0 && teach_in_) {
    // Total resolution = desired units for the distance travelled, scaled to the whole range.
    const std::uint64_t distance = out & bits::position25;
    const std::uint64_t now = coded_physical();
    const std::uint64_t travelled = now > teach_start_ ? now - teach_start_ : teach_start_ - now;
    if (travelled > 0 && distance > 0) {
      const auto total = static_cast<std::uint64_t>(std::llround(
          static_cast<double>(distance) * static_cast<double>(total_) / static_cast<double>(travelled)));
      if (total >= 1 && total <= std::min<std::uint64_t>(total_, bits::position25 + 1ull))
        teach_result_ = static_cast<std::uint32_t>(total);
    }
  }
  if ((falling & bits::teach_in_end) != 0 && teach_result_) finish_teach_in();
}

void EncoderDevice::finish_teach_in() noexcept {
  params_.scaling = true;
  params_.units_select = UnitsSelect::per_total_range;
  params_.measuring_units = *teach_result_;
  scaling_ = Scaling(params_, identity_.physical);
  eeprom_.taught_units = *teach_result_;
  eeprom_.offset = 0;
  teach_in_ = false;
  teach_result_.reset();
  sampled_at_.reset();
}

CyclicInput EncoderDevice::exchange(std::optional<std::uint32_t> output) noexcept {
  if (output) {
    on_edges(*output);
    last_output_ = *output;
  }
  CyclicInput in;
  in.velocity = velocity16_;
  in.acceleration = acceleration16_;
  if (!has_status_bits(params_)) {
    in.word = position() & bits::position31;
    return in;
  }
  const std::uint32_t status = status_word();
  if (direction_ack_) {
    // 4.4.1 row 2: the acknowledge in bit 28 (new sequence) and bit 0 (echo of the request).
    in.word = status | (eeprom_.code_sequence == CodeSequence::ccw ? 1u : 0u);
  } else if (teach_result_) {
    // 4.4.2 "Ending" row 2: bits 29 and 30 set, bits 0–24 the total resolution.
    in.word = status | bits::teach_in_end | (*teach_result_ & bits::position25);
  } else {
    in.word = status | (position() & bits::position25);
  }
  return in;
}

void EncoderDevice::set_alarm(std::uint16_t mask, bool on) noexcept {
  const auto m = static_cast<std::uint8_t>(mask & alarm::supported);
  alarms_ = on ? static_cast<std::uint8_t>(alarms_ | m) : static_cast<std::uint8_t>(alarms_ & ~m);
}

void EncoderDevice::set_warning(std::uint16_t mask, bool on) noexcept {
  const auto m = static_cast<std::uint16_t>(mask & warning::supported);
  warnings_ = on ? static_cast<std::uint16_t>(warnings_ | m) : static_cast<std::uint16_t>(warnings_ & ~m);
}

void EncoderDevice::add_operating_time(link::Duration d) noexcept {
  if (d.count() > 0) operating_time_ns_ += static_cast<std::uint64_t>(d.count());
  if (operating_time_ns_ / kNsPerTenthHour >= kOperatingTimeLimit) warnings_ |= warning::operating_time_limit;
}

EncoderDiagnosis EncoderDevice::diagnosis() const noexcept {
  EncoderDiagnosis d;
  d.alarms = alarms_;
  d.status = OperatingStatus{eeprom_.code_sequence == CodeSequence::ccw,
                             params_.functionality != Functionality::class1, false, scaling_.scaled()};
  d.encoder_type = identity_.physical.revolutions > 1 ? 1 : 0;
  d.singleturn_resolution = identity_.physical.steps_per_revolution;
  d.revolutions = static_cast<std::uint16_t>(identity_.physical.revolutions);
  if (params_.functionality == Functionality::class1 ||
      (is_scancon(params_.functionality) && params_.short_diagnosis))
    return d;
  DiagnosisDetail x;
  x.supported_alarms = alarm::supported;
  x.warnings = warnings_;
  x.supported_warnings = warning::supported;
  x.profile_version = identity_.profile_version;
  x.software_version = identity_.software_version;
  x.operating_time_tenth_h = static_cast<std::uint32_t>(operating_time_ns_ / kNsPerTenthHour);
  x.offset = eeprom_.offset;
  x.units_per_revolution = static_cast<std::uint32_t>(std::llround(scaling_.units_per_revolution()));
  x.total_range = static_cast<std::uint32_t>(scaling_.range());
  x.serial = identity_.serial;
  d.detail = x;
  return d;
}

}  // namespace cellctl::encoder

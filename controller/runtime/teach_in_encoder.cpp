#include "runtime/teach_in_encoder.hpp"

#include <cmath>
#include <stdexcept>

#include "encoder/commissioning_parameters.hpp"

namespace cellctl::runtime {

using routines::EncoderCommand;
using routines::EncoderSetting;

TeachInEncoder::TeachInEncoder(encoder::Session& session, const encoder::SessionConfig& configured)
    : session_(session),
      configured_(configured),
      configured_steps_per_mm_(session.steps_per_mm()),
      units_per_mm_(encoder::teach_in_units_per_mm(configured_steps_per_mm_)),
      target_(configured) {}

std::string_view TeachInEncoder::unavailable() const {
  if (const auto why = encoder::teach_in_unavailable(configured_.parameters); !why.empty()) return why;
  if (units_per_mm_ <= 0.0) return "the encoder resolves less than one step per mm: no unit to teach in";
  return {};
}

encoder::SessionConfig TeachInEncoder::taught(std::uint32_t total_resolution) const {
  auto c = configured_;
  c.parameters = encoder::taught_parameters(configured_.parameters, total_resolution);
  c.counts_per_mm = units_per_mm_;
  c.mm_per_revolution = 0.0;
  // The axis zero stays where it was on the shaft: the same number of physical steps from the
  // native zero, in the new unit (Teach-In needs and leaves offset 0).
  const double total = static_cast<double>(configured_.physical.total());
  const double new_steps_per_mm = units_per_mm_ * total / static_cast<double>(std::max(total_resolution, 1u));
  c.zero_offset_mm = configured_.zero_offset_mm * configured_steps_per_mm_ / new_steps_per_mm;
  c.expected_offset = 0;
  return c;
}

encoder::SessionConfig TeachInEncoder::config_for(EncoderSetting s) const {
  auto c = configured_;
  if (s == EncoderSetting::teach_in) {
    c.parameters = encoder::teach_in_parameters(configured_.parameters, configured_.physical);
    // One unit per physical step: the same length per count whatever the configured scaling was.
    c.counts_per_mm = configured_steps_per_mm_;
    c.mm_per_revolution = 0.0;
    c.zero_offset_mm = 0.0;
  } else if (s == EncoderSetting::taught) {
    c = taught(total_resolution_);
  }
  return c;
}

void TeachInEncoder::switch_to(EncoderSetting setting, link::TimePoint now) {
  target_ = config_for(setting);
  failure_ = {};
  session_.deactivate(now);
  pending_ = true;
}

void TeachInEncoder::step(link::TimePoint now) {
  if (!pending_ || !session_.quiet()) return;
  pending_ = false;
  try {
    if (!session_.reconfigure(target_)) {
      failure_ = "the session did not close for the new parameters";
      return;
    }
  } catch (const std::invalid_argument&) {
    failure_ = "the new parameters were refused by the session";
    return;
  }
  session_.activate(now);
}

void TeachInEncoder::clear_command() {
  const auto& c = session_.snapshot().command;
  if (c.kind == encoder::Handshake::Kind::teach_in_end && c.phase == encoder::Handshake::Phase::done)
    total_resolution_ = c.result;
  session_.clear_command();
}

bool TeachInEncoder::start_teach_in() {
  return session_.teach_in_start();
}

bool TeachInEncoder::end_teach_in(double distance_mm) {
  const double units = std::round(distance_mm * units_per_mm_);
  if (units < 1.0 || units >= static_cast<double>(1u << 25)) return false;  // bits 0–24 (4.4.2.1)
  return session_.teach_in_end(static_cast<std::uint32_t>(units));
}

routines::EncoderView TeachInEncoder::read() const {
  const auto& s = session_.snapshot();
  routines::EncoderView r;
  const bool active = session_.lifecycle() == link::Lifecycle::active;
  r.teach_in_running = s.has_status_bits && (s.status.teach_in_start || s.status.teach_in_end);
  r.up = !pending_ && active && s.data_exchange && (!s.has_status_bits || s.status.ready) && s.exchanges > 2;
  r.position_mm = s.position_mm;
  r.native_range_mm = static_cast<double>(configured_.physical.total()) / configured_steps_per_mm_;
  if (s.diagnosis && s.diagnosis->detail) r.stored_offset = s.diagnosis->detail->offset;
  switch (s.command.phase) {
    case encoder::Handshake::Phase::done:
      r.command = EncoderCommand::done;
      break;
    case encoder::Handshake::Phase::failed:
      r.command = EncoderCommand::failed;
      break;
    case encoder::Handshake::Phase::idle:
      r.command = EncoderCommand::idle;
      break;
    default:
      r.command = EncoderCommand::busy;
      break;
  }
  r.total_resolution = s.command.result;
  if (!failure_.empty())
    r.failure = failure_;
  else if (!s.command.failure.empty())
    r.failure = s.command.failure;
  else if (!pending_ && session_.lifecycle() == link::Lifecycle::fault)
    r.failure = session_.fault_reason();
  return r;
}

}  // namespace cellctl::runtime

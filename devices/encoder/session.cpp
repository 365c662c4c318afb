#include "encoder/session.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <variant>

#include "link/fault_reason.hpp"

namespace cellctl::encoder {
namespace {

profibus::DpSlaveSetup slave_setup(const SessionConfig& c) {
  profibus::DpSlaveSetup s;
  s.station_address = c.station_address;
  s.ident = kIdentNumber;
  std::array<std::uint8_t, 64> prm{};
  s.user_prm.assign(std::span(prm).first(encode_user_prm(c.parameters, prm)));
  s.cfg.assign(config_identifiers(c.parameters.functionality));
  s.input_length = input_length(c.parameters.functionality);
  s.output_length = output_length(c.parameters.functionality);
  return s;
}

double length_per_count(const SessionConfig& c, const Scaling& scaling) {
  if (c.counts_per_mm > 0.0 && c.mm_per_revolution > 0.0)
    throw std::invalid_argument("encoder session: give counts_per_mm or mm_per_revolution, not both");
  if (const double upm = units_per_mm(c.counts_per_mm, c.mm_per_revolution, scaling); upm > 0.0) return upm;
  throw std::invalid_argument(
      fmt::format("encoder session: counts_per_mm {} / mm_per_revolution {}: one must be > 0",
                  c.counts_per_mm, c.mm_per_revolution));
}

}  // namespace

Session::Session(link::Link& link, const SessionConfig& config)
    : config_(config),
      scaling_(config.parameters, config.physical),
      counts_per_mm_(length_per_count(config, scaling_)),
      master_(link, config.bus, slave_setup(config)) {
  snapshot_.has_status_bits = has_status_bits(config_.parameters);
}

bool Session::reconfigure(const SessionConfig& config) {
  if (lifecycle() != link::Lifecycle::inactive && lifecycle() != link::Lifecycle::fault) return false;
  if (master_.lifecycle() != link::Lifecycle::inactive && master_.lifecycle() != link::Lifecycle::fault)
    return false;
  Scaling scaling(config.parameters, config.physical);
  const double per_mm = length_per_count(config, scaling);
  master_.set_slave_setup(slave_setup(config));
  config_ = config;
  scaling_ = scaling;
  counts_per_mm_ = per_mm;
  snapshot_ = Snapshot{};
  snapshot_.has_status_bits = has_status_bits(config_.parameters);
  seen_exchanges_ = master_.stats().data_exchanges;
  seen_diag_reads_ = master_.stats().diag_reads;
  return true;
}

double Session::steps_per_mm() const noexcept {
  return counts_per_mm_ * static_cast<double>(config_.physical.steps_per_revolution) /
         scaling_.units_per_revolution();
}

void Session::activate(link::TimePoint now) {
  handshake_.reset();
  offset_refused_ = false;
  output_word_ = 0;
  snapshot_.local_prm_violation = validate(config_.parameters, config_.physical);
  if (snapshot_.local_prm_violation) {
    // Never send parameters the encoder would refuse: say which rule, here.
    enter_fault("parameters refused before sending: {}", snapshot_.local_prm_violation->describe());
    return;
  }
  enter(link::Lifecycle::activating, now);
  if (has_outputs(config_.parameters.functionality)) {
    std::array<std::uint8_t, 4> zero{};
    (void)master_.set_outputs(zero);  // the 4 output octets the encoder's functionality configures
  }
  master_.activate(now);
  update_lifecycle();
}

void Session::deactivate(link::TimePoint now) {
  handshake_.abort("session deactivated during the handshake");
  master_.deactivate(now);
  update_lifecycle();
}

void Session::transmit(link::TimePoint) {
  if (!snapshot_.local_prm_violation) push_outputs();
}

void Session::receive(link::TimePoint now) {
  if (snapshot_.local_prm_violation) return;
  (void)master_.poll(now);  // its lifecycle is taken below (update_lifecycle)
  const auto& stats = master_.stats();
  if (stats.data_exchanges != seen_exchanges_) {
    seen_exchanges_ = stats.data_exchanges;
    on_input(master_.inputs());
  }
  bool fresh_diagnosis = false;
  if (stats.diag_reads != seen_diag_reads_) {
    fresh_diagnosis = true;
    seen_diag_reads_ = stats.diag_reads;
    const auto& diag = master_.diagnosis();
    snapshot_.standard_diag = diag.standard;
    snapshot_.extended_diag_octets = diag.extended.size();
    snapshot_.diagnosis_error = {};
    if (!diag.extended.empty()) {
      auto decoded = decode_diagnosis(diag.extended.view());
      if (auto* d = std::get_if<EncoderDiagnosis>(&decoded))
        snapshot_.diagnosis = *d;
      else
        snapshot_.diagnosis_error = to_string(std::get<DiagError>(decoded));
    }
    snapshot_.diagnosis_reads = seen_diag_reads_;
    check_offset();
    if (offset_refused_) master_.deactivate(now);
  }
  const auto state = master_.dp_state();
  snapshot_.dp_state = state;
  snapshot_.data_exchange =
      state == profibus::DpState::data_exchange || state == profibus::DpState::diag_cyclic;
  // A diagnosis the encoder raised (DH) while exchanging data, as opposed to the start-up's reads.
  snapshot_.new_diagnosis = fresh_diagnosis && snapshot_.data_exchange;
  snapshot_.exchanges = seen_exchanges_;
  snapshot_.input_age = master_.input_age(now);
  snapshot_.had_valid_input = stats.last_input_at.has_value();
  snapshot_.bad_inputs = stats.bad_inputs;
  if (!snapshot_.data_exchange) snapshot_.input_valid = false;
  snapshot_.startup_fault = master_.last_startup_fault().kind;
  if (!snapshot_.data_exchange && handshake_.busy()) {
    handshake_.abort("data exchange lost during the handshake");
    push_outputs();
  }
  snapshot_.command =
      CommandStatus{handshake_.kind(), handshake_.phase(), handshake_.result(), handshake_.failure()};
  update_lifecycle();
}

void Session::check_offset() noexcept {
  if (offset_refused_ || !config_.expected_offset || !snapshot_.diagnosis || !snapshot_.diagnosis->detail)
    return;
  const std::int32_t stored = snapshot_.diagnosis->detail->offset;
  if (stored == *config_.expected_offset) return;
  offset_refused_ = true;
  // Positions would be off by the difference: never let them reach the cell. Said with both values.
  enter_fault(
      "the encoder holds preset offset {} (its EEPROM, diagnosis octets 32-35), this config expects "
      "encoder.preset_offset: {}: it was preset since the config was written. Preset it again with "
      "`cellctl encoder preset` (which records the offset in the config), or set preset_offset: {} if the "
      "new zero is wanted",
      stored, *config_.expected_offset, stored);
}

void Session::update_lifecycle() {
  if (offset_refused_) return;  // a fault of its own, kept until the next activation
  const link::Lifecycle lc = master_.lifecycle();
  if (lc != link::Lifecycle::fault) {
    if (lc != lifecycle()) enter(lc);
    return;
  }
  if (lifecycle() == link::Lifecycle::fault) return;  // its reason is written once per fault
  // Formatted into the capacity reserved at construction: the cycle does not allocate for it.
  const std::string_view reason = master_.fault_reason();
  const auto& physical = config_.physical;
  if (snapshot_.startup_fault == profibus::StartupFault::Kind::prm_fault) {
    // The slave does not say which rule: the local check passed, so its resolution must differ.
    if (snapshot_.diagnosis)
      enter_fault(
          "{} (parameters pass the local check for {} steps × {} revolutions; the encoder reports {} × {})",
          reason, physical.steps_per_revolution, physical.revolutions,
          snapshot_.diagnosis->singleturn_resolution, snapshot_.diagnosis->revolutions);
    else
      enter_fault("{} (parameters pass the local check for {} steps × {} revolutions)", reason,
                  physical.steps_per_revolution, physical.revolutions);
  } else if (snapshot_.startup_fault == profibus::StartupFault::Kind::cfg_fault) {
    enter_fault("{} (the encoder refused configuration {} with these parameters)", reason,
                to_string(config_.parameters.functionality));
  } else {
    enter_fault("{}", reason);
  }
}

// Why the encoder's own bits say this input's position is not a position now (empty: it is one).
std::string_view Session::flagged(const CyclicInput& in) const noexcept {
  if (!snapshot_.has_status_bits) return {};
  const StatusBits st = in.status();
  if (!st.ready) return "the encoder clears its Ready bit";
  if (st.teach_in_start || st.teach_in_end) return "Teach-In running: the position is unscaled";
  if (handshake_.kind() == Handshake::Kind::direction && handshake_.phase() == Handshake::Phase::request)
    return "direction change acknowledged in the position bits";
  return {};
}

void Session::on_input(std::span<const std::uint8_t> bytes) noexcept {
  const bool with_status = snapshot_.has_status_bits;
  auto decoded = decode_input(config_.parameters.functionality, with_status, bytes);
  const auto* in = std::get_if<CyclicInput>(&decoded);
  if (in == nullptr) {
    // Not the shape the manual allows: nothing of it is a measurement.
    snapshot_.input_valid = false;
    snapshot_.input_fault = to_string(std::get<CyclicError>(decoded));
    master_.reject_input();
    return;
  }
  snapshot_.input_fault = flagged(*in);
  snapshot_.input_valid = snapshot_.input_fault.empty();
  if (!snapshot_.input_valid) master_.reject_input();
  const TimeBase tb = config_.parameters.time_base;
  const double upr = scaling_.units_per_revolution();
  snapshot_.position_counts = in->position(with_status);
  // Teach-In runs unscaled over the physical range (4.4.2.1); otherwise the scaled range rolls over.
  const bool unscaled = with_status && (in->status().teach_in_start || in->status().teach_in_end);
  const std::uint64_t range = unscaled ? config_.physical.total() : scaling_.range();
  const auto counts = static_cast<std::int64_t>(snapshot_.position_counts);
  const auto half = static_cast<std::int64_t>(range / 2);
  const std::int64_t signed_counts = counts >= half ? counts - static_cast<std::int64_t>(range) : counts;
  const double per_mm = unscaled ? steps_per_mm() : counts_per_mm_;
  snapshot_.position_mm =
      static_cast<double>(signed_counts) / per_mm - (unscaled ? 0.0 : config_.zero_offset_mm);
  snapshot_.velocity_raw = in->velocity;
  snapshot_.velocity_saturated = saturated(in->velocity);
  snapshot_.velocity_mm_s = units_per_second(in->velocity, tb, upr) / counts_per_mm_;
  snapshot_.acceleration_raw = in->acceleration;
  snapshot_.acceleration_saturated = saturated(in->acceleration);
  snapshot_.acceleration_mm_s2 =
      units_per_second(in->acceleration, tb, upr) / counts_per_mm_ / link::to_seconds(sample_period(tb));
  if (with_status) snapshot_.status = in->status();
  // The first reply after an output change may answer a request sent before it: skip it.
  if (handshake_.busy() && seen_exchanges_ > outputs_changed_at_ + 1) {
    handshake_.on_input(*in);
    push_outputs();
  }
}

void Session::push_outputs() noexcept {
  if (!has_outputs(config_.parameters.functionality)) return;
  const std::uint32_t w = handshake_.output();
  if (w == output_word_) return;
  std::array<std::uint8_t, 4> out{};
  (void)encode_output(w, out);  // always the 4 octets of `out`
  if (master_.set_outputs(out)) {
    output_word_ = w;
    outputs_changed_at_ = seen_exchanges_;
  }
}

bool Session::manufacturer_function_allowed() const noexcept {
  return snapshot_.data_exchange && !handshake_.busy() && has_status_bits(config_.parameters) &&
         config_.parameters.commissioning;
}

bool Session::preset(std::uint32_t value) noexcept {
  if (!snapshot_.data_exchange || !has_outputs(config_.parameters.functionality) || handshake_.busy())
    return false;
  if (value >= scaling_.range()) return false;  // 4.3.2: at most Total Measuring Range − 1
  if (!handshake_.start_preset(value, snapshot_.has_status_bits)) return false;
  push_outputs();
  return true;
}

bool Session::set_direction(CodeSequence wanted) noexcept {
  if (!manufacturer_function_allowed() || !handshake_.start_direction(wanted)) return false;
  push_outputs();
  return true;
}

bool Session::teach_in_start() noexcept {
  if (!manufacturer_function_allowed() || !handshake_.start_teach_in()) return false;
  push_outputs();
  return true;
}

bool Session::teach_in_end(std::uint32_t distance) noexcept {
  if (!manufacturer_function_allowed() || !handshake_.end_teach_in(distance)) return false;
  push_outputs();
  return true;
}

void Session::clear_command() noexcept {
  if (handshake_.busy()) return;
  handshake_.reset();
  snapshot_.command = CommandStatus{};
}

bool Session::set_slave_address(std::uint8_t new_address) noexcept {
  return master_.set_slave_address(new_address, false);
}

}  // namespace cellctl::encoder

#include "encoder/emulator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <variant>

#include "encoder/eeprom_file.hpp"

namespace cellctl::encoder {
namespace {

NonVolatile initial_eeprom(const EmulatorConfig& c) {
  if (c.address < 1 || c.address > 126)
    throw std::invalid_argument(fmt::format("encoder emulator: address {}: must be 1..126", c.address));
  if (auto v = validate(c.identity.physical))
    throw std::invalid_argument("encoder emulator: " + v->describe());
  return c.state_file.empty() ? NonVolatile{} : load_eeprom(c.state_file);
}

}  // namespace

std::uint8_t Emulator::start_address(const EmulatorConfig& c, const NonVolatile& nv) {
  // Only with the switches at 126 does an address set over the bus apply (manual 3.4).
  if (c.address == 126 && nv.address >= 1 && nv.address <= 125) return nv.address;
  return c.address;
}

Emulator::Emulator(link::Link& link, const EmulatorConfig& config, const plant::Shaft& shaft)
    : config_(config),
      shaft_(shaft),
      saved_(initial_eeprom(config_)),
      behaviour_(config_, saved_),
      slave_(link,
             profibus::DpSlaveConfig{.address = start_address(config_, saved_),
                                     .ident = kIdentNumber,
                                     .line = config_.line,
                                     .address_change_allowed = config_.address == 126,
                                     .freeze_supported = true,
                                     .sync_supported = true},
             behaviour_) {
  EncoderParameters p;  // until the first Set_Prm: the defaults, the stored direction
  p.code_sequence = saved_.code_sequence;
  behaviour_.device.parameterize(p);
}

void Emulator::poll(link::TimePoint now) {
  if (last_poll_) behaviour_.device.add_operating_time(now - *last_poll_);
  last_poll_ = now;
  behaviour_.device.sample(shaft_.revolutions(), now);
  slave_.poll(now);
  if (!config_.state_file.empty() && behaviour_.device.eeprom() != saved_) {
    saved_ = behaviour_.device.eeprom();
    // A failed save loses only the EEPROM's continuity into the next dry run (it starts from defaults).
    (void)save_eeprom(config_.state_file, saved_);
  }
}

void Emulator::set_alarm(std::uint16_t mask, bool on) noexcept {
  behaviour_.device.set_alarm(mask, on);
  behaviour_.diag_changed = true;
}

void Emulator::set_warning(std::uint16_t mask, bool on) noexcept {
  behaviour_.device.set_warning(mask, on);
  behaviour_.diag_changed = true;
}

namespace {

// The family the User_Prm_Data length names (4.1: octets 8–9, 8–25, 8–39), as the functionality whose
// rules are the widest of it: Scancon 3.0 for the three Scancon functionalities.
std::optional<Functionality> family_of_prm_length(std::size_t octets) noexcept {
  for (const Functionality f : {Functionality::class1, Functionality::class2, Functionality::scancon30})
    if (user_prm_length(f) == octets) return f;
  return std::nullopt;
}

}  // namespace

profibus::PrmVerdict Emulator::Behaviour::check_prm(std::span<const std::uint8_t> user_prm) {
  accepted_family.reset();
  const auto family = family_of_prm_length(user_prm.size());
  if (!family) {
    prm_reason = fmt::format(
        "User_Prm_Data: {} octets; the encoder takes 2 (Class 1), 18 (Class 2) or 32 (Scancon 2.1/2.2/3.0) "
        "(manual 4.1)",
        user_prm.size());
    return {false, prm_reason};
  }
  auto decoded = decode_user_prm(*family, user_prm);
  if (const auto* v = std::get_if<PrmViolation>(&decoded)) {
    prm_reason = v->describe();
    return {false, prm_reason};
  }
  if (auto v = validate(std::get<EncoderParameters>(decoded), config.identity.physical)) {
    prm_reason = v->describe();
    return {false, prm_reason};
  }
  prm_reason.clear();
  (void)accepted_prm.assign(user_prm);  // at most 32 octets (its family's length, checked above)
  accepted_family = family;
  return {true, {}};
}

bool Emulator::Behaviour::check_cfg(std::span<const std::uint8_t> cfg) {
  const auto f = functionality_of_cfg(cfg);
  if (!f) {
    cfg_reason = "the configuration identifiers name no functionality of the encoder (GSD modules)";
    return false;
  }
  if (!accepted_family || user_prm_length(*f) != user_prm_length(*accepted_family)) {
    cfg_reason = fmt::format("configuration {} does not fit the {}-octet User_Prm_Data of the Set_Prm",
                             to_string(*f), accepted_prm.size());
    return false;
  }
  // The same octets, now judged for the functionality chosen (e.g. Without Status Bits: 3.0 only).
  auto decoded = decode_user_prm(*f, accepted_prm.view());
  if (const auto* v = std::get_if<PrmViolation>(&decoded)) {
    cfg_reason = fmt::format("parameters not allowed with {}: {}", to_string(*f), v->describe());
    return false;
  }
  cfg_reason.clear();
  device.parameterize(std::get<EncoderParameters>(decoded));
  return true;
}

std::size_t Emulator::Behaviour::ext_diag(std::span<std::uint8_t> out) {
  diag_changed = false;
  return encode_diagnosis(device.diagnosis(), out);
}

std::size_t Emulator::Behaviour::exchange(std::span<const std::uint8_t> outputs,
                                          std::span<std::uint8_t> inputs) {
  const Functionality f = functionality();
  std::optional<std::uint32_t> word;
  if (has_outputs(f)) word = decode_output(outputs);
  // A Class 2+ exchange without a 4-octet output (cannot happen after Chk_Cfg) counts as zeros.
  if (has_outputs(f) && !word) word = 0;
  const auto length = encode_input(f, device.exchange(word), inputs);
  if (inputs_all_ones) std::fill_n(inputs.begin(), length, std::uint8_t{0xff});
  return length;
}

void Emulator::Behaviour::on_address_changed(std::uint8_t new_address, bool) {
  device.set_stored_address(new_address);
}

}  // namespace cellctl::encoder

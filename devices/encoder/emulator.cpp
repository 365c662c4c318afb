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
  EncoderParameters p;  // until the first Set_Prm: the functionality's defaults, the stored direction
  p.functionality = config_.functionality;
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

profibus::PrmVerdict Emulator::Behaviour::check_prm(std::span<const std::uint8_t> user_prm) {
  auto decoded = decode_user_prm(config.functionality, user_prm);
  if (const auto* v = std::get_if<PrmViolation>(&decoded)) {
    prm_reason = v->describe();
    return {false, prm_reason};
  }
  const auto& p = std::get<EncoderParameters>(decoded);
  if (auto v = validate(p, config.identity.physical)) {
    prm_reason = v->describe();
    return {false, prm_reason};
  }
  prm_reason.clear();
  device.parameterize(p);
  return {true, {}};
}

bool Emulator::Behaviour::check_cfg(std::span<const std::uint8_t> cfg) {
  return std::ranges::equal(cfg, config_identifiers(config.functionality));
}

std::size_t Emulator::Behaviour::ext_diag(std::span<std::uint8_t> out) {
  diag_changed = false;
  return encode_diagnosis(device.diagnosis(), out);
}

std::size_t Emulator::Behaviour::exchange(std::span<const std::uint8_t> outputs,
                                          std::span<std::uint8_t> inputs) {
  std::optional<std::uint32_t> word;
  if (has_outputs(config.functionality)) word = decode_output(outputs);
  // A Class 2+ exchange without a 4-octet output (cannot happen after Chk_Cfg) counts as zeros.
  if (has_outputs(config.functionality) && !word) word = 0;
  return encode_input(config.functionality, device.exchange(word), inputs);
}

void Emulator::Behaviour::on_address_changed(std::uint8_t new_address, bool) {
  device.set_stored_address(new_address);
}

}  // namespace cellctl::encoder

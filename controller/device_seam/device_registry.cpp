#include "device_seam/device_registry.hpp"

#include <array>
#include <vector>

#include "device_seam/encoder_device.hpp"
#include "device_seam/scu_device.hpp"
#include "device_seam/spindle_device.hpp"
#include "emulation/device_emulators.hpp"

namespace cellctl::device_seam {
namespace {

// The port of the cell's section `section`, when it has one.
template <auto section>
std::optional<config::PortConfig> port_of(const config::CellConfig& cell) {
  if (!(cell.*section)) return std::nullopt;
  return (cell.*section)->port;
}

template <class T>
std::unique_ptr<CellDevice> make(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                                 CellDevice::Reopen reopen) {
  return std::make_unique<T>(slot, cell, link, std::move(reopen));
}

constexpr std::array kKinds{
    DeviceKind{"scu", "every actuator reports an actuator fault (error code bits 15..20) and is fast-stopped",
               &port_of<&config::CellConfig::scu>, &make<ScuDevice>, &emulation::make_scu_emulator},
    DeviceKind{"spindle", "the converter latches fault 31, motor over-temperature, and runs the motor down",
               &port_of<&config::CellConfig::spindle>, &make<SpindleDevice>,
               &emulation::make_spindle_emulator},
    DeviceKind{"encoder", "the encoder reports the position error alarm in its diagnosis",
               &port_of<&config::CellConfig::encoder>, &make<EncoderDevice>,
               &emulation::make_encoder_emulator},
};
static_assert(kKinds.size() == cell::kDevices, "one kind per cell::Device, in its order");

}  // namespace

std::span<const DeviceKind> cell_device_kinds() noexcept {
  return kKinds;
}

const DeviceKind* find_kind(std::span<const DeviceKind> kinds, std::string_view name) noexcept {
  for (const auto& k : kinds)
    if (k.name == name) return &k;
  return nullptr;
}

config::CellConfig load_cell_config(const std::filesystem::path& path, std::span<const DeviceKind> kinds) {
  return parse_cell_config(config::YamlNode::load_file(path), path, kinds);
}

config::CellConfig parse_cell_config(const config::YamlNode& root, const std::filesystem::path& source,
                                     std::span<const DeviceKind> kinds) {
  std::vector<std::string_view> sections;
  for (const auto& k : kinds) sections.push_back(k.name);
  auto cell = config::parse_cell_config(root, source, sections);
  for (const auto& k : kinds) (void)k.port(cell);  // read for its errors; opened later
  return cell;
}

}  // namespace cellctl::device_seam

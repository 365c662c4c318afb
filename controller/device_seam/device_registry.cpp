#include "device_seam/device_registry.hpp"

#include <array>

#include "device_seam/encoder_device.hpp"
#include "device_seam/scu_device.hpp"
#include "device_seam/spindle_device.hpp"

namespace cellctl::device_seam {
namespace {

// The device of type T when the cell's config has its section (`section`).
template <class T, auto section>
std::unique_ptr<CellDevice> make(std::size_t slot, const config::CellConfig& cell, link::Link& link,
                                 CellDevice::Reopen reopen) {
  if (!(cell.*section)) return nullptr;
  return std::make_unique<T>(slot, cell, link, std::move(reopen));
}

constexpr std::array kKinds{
    DeviceKind{"scu", &make<ScuDevice, &config::CellConfig::scu>},
    DeviceKind{"spindle", &make<SpindleDevice, &config::CellConfig::spindle>},
    DeviceKind{"encoder", &make<EncoderDevice, &config::CellConfig::encoder>},
};
static_assert(kKinds.size() == cell::kDevices, "one kind per cell::Device, in its order");

}  // namespace

std::span<const DeviceKind> cell_device_kinds() noexcept {
  return kKinds;
}

}  // namespace cellctl::device_seam

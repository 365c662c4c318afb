#pragma once
// The emulators of the cell's three devices as EmulatedDevices, and how each is made for the registry
// (device_seam/device_registry.cpp). Each returns nullptr when the set-up has no emulator for it.

#include <memory>

#include "emulation/emulated_device.hpp"
#include "encoder/emulator.hpp"
#include "plant/shaft.hpp"
#include "scu/emulator.hpp"
#include "spindle/emulator.hpp"

namespace cellctl::emulation {

// Every actuator reports an actuator fault (error code bits 15..20) as its own error.
[[nodiscard]] std::unique_ptr<EmulatedDevice> make_scu_emulator(const EmulatorContext& context);
// Fault 31, the motor's over-temperature, latched: its own error.
[[nodiscard]] std::unique_ptr<EmulatedDevice> make_spindle_emulator(const EmulatorContext& context);
// The encoder on a shaft that turns with the SCU actuator of the measured axis (made before it); the
// position error alarm of its extended diagnosis is its own error. Throws std::invalid_argument without
// that actuator.
[[nodiscard]] std::unique_ptr<EmulatedDevice> make_encoder_emulator(const EmulatorContext& context);

// The emulated encoder's shaft (plant::Shaft), for a test that turns or slips it.
class EmulatedEncoder : public EmulatorOf<encoder::Emulator> {
 public:
  [[nodiscard]] virtual plant::Shaft& shaft() noexcept = 0;
};

}  // namespace cellctl::emulation

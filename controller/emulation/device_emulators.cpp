#include "emulation/device_emulators.hpp"

#include <optional>
#include <stdexcept>

#include "encoder/diagnosis.hpp"
#include "encoder/scaling.hpp"

namespace cellctl::emulation {
namespace {

class ScuEmulated final : public EmulatorOf<scu::Emulator> {
 public:
  ScuEmulated(link::Link& link, const scu::EmulatorConfig& config) : emulator_(link, config) {}
  scu::Emulator& emulator() noexcept override { return emulator_; }
  void poll(link::TimePoint now) override { emulator_.poll(now); }
  void set_own_error(bool on) override {
    for (int a = 1; a <= scu::kActuatorCount; ++a)
      if (emulator_.has_actuator(a)) emulator_.set_actuator_fault(a, on);
  }

 private:
  scu::Emulator emulator_;
};

class SpindleEmulated final : public EmulatorOf<spindle::Emulator> {
 public:
  SpindleEmulated(link::Link& link, const spindle::EmulatorConfig& config) : emulator_(link, config) {}
  spindle::Emulator& emulator() noexcept override { return emulator_; }
  void poll(link::TimePoint now) override { emulator_.poll(now); }
  void set_own_error(bool on) override { emulator_.set_over_temperature(on); }

 private:
  spindle::Emulator emulator_;
};

// The shaft's lead: the plant's (plant.encoder_mm_per_revolution) when given — mechanics, the same
// whatever the encoder was taught. Otherwise what the encoder session takes a revolution to be, so
// that a perfect coupling reads the axis exactly; slip is the plant's deviation from it. The session
// reads position_mm as measuring units ÷ counts_per_mm, and a revolution is the session's units per
// revolution — scaled units when scaling is on, not physical steps (encoder::Session's length per
// count). That fallback follows the config: after a Teach-In (which writes counts_per_mm and the
// taught resolution) it is the taught belief, so each Teach-In would turn a different shaft.
double mm_per_revolution(const config::EncoderSection& e, const PlantConfig& plant) {
  if (plant.encoder_mm_per_revolution > 0.0) return plant.encoder_mm_per_revolution;
  if (e.session.mm_per_revolution > 0.0) return e.session.mm_per_revolution;
  const encoder::Scaling scaling(e.session.parameters, e.session.physical);
  return scaling.units_per_revolution() / e.session.counts_per_mm;
}

class EncoderEmulated final : public EmulatedEncoder {
 public:
  EncoderEmulated(const EmulatorContext& c, const plant::Actuator& actuator)
      : shaft_(shaft_params(c), [&actuator] { return actuator.true_position_mm(); }),
        emulator_(c.link, *c.setup.encoder, shaft_) {}
  encoder::Emulator& emulator() noexcept override { return emulator_; }
  plant::Shaft& shaft() noexcept override { return shaft_; }
  void poll(link::TimePoint now) override { emulator_.poll(now); }
  void set_own_error(bool on) override { emulator_.set_alarm(encoder::alarm::position_error, on); }

 private:
  static plant::ShaftParams shaft_params(const EmulatorContext& c) {
    const double per_revolution = mm_per_revolution(*c.cell.encoder, c.setup.plant);
    return {.mm_per_revolution = per_revolution,
            .slip = c.setup.plant.encoder_slip,
            .offset_revolutions = c.setup.plant.encoder_mount_mm / per_revolution};
  }

  plant::Shaft shaft_;  // before the emulator, which reads it
  encoder::Emulator emulator_;
};

}  // namespace

std::unique_ptr<EmulatedDevice> make_scu_emulator(const EmulatorContext& c) {
  if (!c.setup.scu) return nullptr;
  return std::make_unique<ScuEmulated>(c.link, *c.setup.scu);
}

std::unique_ptr<EmulatedDevice> make_spindle_emulator(const EmulatorContext& c) {
  if (!c.setup.spindle) return nullptr;
  return std::make_unique<SpindleEmulated>(c.link, *c.setup.spindle);
}

std::unique_ptr<EmulatedDevice> make_encoder_emulator(const EmulatorContext& c) {
  if (!c.cell.encoder || !c.setup.encoder) return nullptr;
  const config::AxisConfig* measured = nullptr;
  for (const auto& a : c.cell.axes)
    if (a.encoder) measured = &a;
  auto* scu = find_emulator<scu::Emulator>(c.made);
  if (!measured || !scu)
    throw std::invalid_argument(
        "an emulated encoder needs an emulated SCU axis to turn its shaft (axes[].encoder)");
  return std::make_unique<EncoderEmulated>(c, scu->actuator(measured->actuator));
}

}  // namespace cellctl::emulation

#include "runtime/emulated_cell.hpp"

#include <stdexcept>

#include "encoder/scaling.hpp"
#include "runtime/plant_state.hpp"

namespace cellctl::runtime {
namespace {

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

}  // namespace

namespace {

EmulatorSetup starting_state(const EmulatorSetup& setup) {
  if (setup.plant_state_file.empty()) return setup;
  auto state = load_plant_state(setup.plant_state_file);
  if (setup.power_cycle) state = power_cycled(state);
  EmulatorSetup started = setup;
  start_from(started, state);
  return started;
}

}  // namespace

EmulatedCell::EmulatedCell(const config::CellConfig& cell, const EmulatorSetup& given, DeviceLinks links)
    : plant_state_file_(given.plant_state_file) {
  const EmulatorSetup setup = starting_state(given);
  if (links.scu && setup.scu) scu_ = std::make_unique<scu::Emulator>(*links.scu, *setup.scu);
  if (links.spindle && setup.spindle)
    spindle_ = std::make_unique<spindle::Emulator>(*links.spindle, *setup.spindle);
  if (links.encoder && cell.encoder && setup.encoder) {
    const config::AxisConfig* measured = nullptr;
    for (const auto& a : cell.axes)
      if (a.encoder) measured = &a;
    if (!measured || !scu_)
      throw std::invalid_argument(
          "an emulated encoder needs an emulated SCU axis to turn its shaft (axes[].encoder)");
    const plant::Actuator& actuator = scu_->actuator(measured->actuator);
    const double per_revolution = mm_per_revolution(*cell.encoder, setup.plant);
    shaft_.emplace(plant::ShaftParams{.mm_per_revolution = per_revolution,
                                      .slip = setup.plant.encoder_slip,
                                      .offset_revolutions = setup.plant.encoder_mount_mm / per_revolution},
                   [&actuator] { return actuator.true_position_mm(); });
    encoder_ = std::make_unique<encoder::Emulator>(*links.encoder, *setup.encoder, *shaft_);
  }
}

EmulatedCell::~EmulatedCell() {
  // A failed save loses only the dry runs' continuity: the next one starts as after a power loss.
  if (!plant_state_file_.empty()) (void)save_plant_state(plant_state_file_, plant_state_of(*this));
}

void EmulatedCell::poll(link::TimePoint now) {
  if (scu_) scu_->poll(now);
  if (spindle_) spindle_->poll(now);
  if (encoder_) encoder_->poll(now);
}

}  // namespace cellctl::runtime

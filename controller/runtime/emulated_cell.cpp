#include "runtime/emulated_cell.hpp"

#include <stdexcept>

#include "runtime/plant_state.hpp"

namespace cellctl::runtime {
namespace {

emulation::EmulatorSetup starting_state(const emulation::EmulatorSetup& setup) {
  if (setup.plant_state_file.empty()) return setup;
  auto state = load_plant_state(setup.plant_state_file);
  if (setup.power_cycle) state = power_cycled(state);
  emulation::EmulatorSetup started = setup;
  start_from(started, state);
  return started;
}

}  // namespace

EmulatedCell::EmulatedCell(const config::CellConfig& cell, const emulation::EmulatorSetup& given,
                           const DeviceLinks& links, std::span<const device_seam::DeviceKind> kinds)
    : plant_state_file_(given.plant_state_file) {
  if (kinds.size() > cell::kMaxDevices) throw std::invalid_argument("more devices than a cell has slots for");
  const emulation::EmulatorSetup setup = starting_state(given);
  for (std::size_t slot = 0; slot < kinds.size(); ++slot) {
    if (!links[slot] || !kinds[slot].make_emulator) continue;
    owned_[slot] =
        kinds[slot].make_emulator({.cell = cell, .setup = setup, .link = *links[slot], .made = made_});
    made_[slot] = owned_[slot].get();
  }
}

EmulatedCell::~EmulatedCell() {
  // A failed save loses only the dry runs' continuity: the next one starts as after a power loss.
  if (!plant_state_file_.empty()) (void)save_plant_state(plant_state_file_, plant_state_of(*this));
}

void EmulatedCell::poll(link::TimePoint now) {
  for (auto* d : made_)
    if (d) d->poll(now);
}

plant::Shaft* EmulatedCell::shaft() noexcept {
  for (auto* d : made_)
    if (auto* e = dynamic_cast<emulation::EmulatedEncoder*>(d)) return &e->shaft();
  return nullptr;
}

}  // namespace cellctl::runtime

#include "runtime/plant_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "config/config_edit.hpp"
#include "runtime/emulated_cell.hpp"
#include "schema/state_files.hpp"

namespace cellctl::runtime {

PlantState load_plant_state(const std::filesystem::path& path) {
  PlantState state;
  std::ifstream in(path);
  if (!in) return state;
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto not_the_state = [&](std::string_view what) {
    return std::runtime_error(fmt::format(
        "{}: not the emulated plant's state ({}); delete it to start the emulators as after power-up",
        path.string(), what));
  };
  auto read = schema::read_plant_state_json(text);
  if (const auto* why = std::get_if<std::string>(&read)) throw not_the_state(*why);
  const auto& kept = std::get<schema::PlantStateFile>(read);
  for (const auto& a : kept.scu_actuators) {
    if (a.actuator < 1 || a.actuator > scu::kActuatorCount) throw not_the_state("actuator out of range");
    state.actuators[static_cast<std::size_t>(a.actuator - 1)] =
        PlantState::Actuator{a.position_mm, a.initialised};
  }
  if (kept.spindle) {
    state.spindle_converter_hours = kept.spindle->converter_hours;
    state.spindle_motor_hours = kept.spindle->motor_hours;
  }
  return state;
}

bool save_plant_state(const std::filesystem::path& path, const PlantState& state) noexcept {
  try {
    schema::PlantStateFile kept;
    for (std::size_t i = 0; i < state.actuators.size(); ++i)
      if (const auto& a = state.actuators[i])
        kept.scu_actuators.push_back({static_cast<int>(i + 1), a->position_mm, a->initialised});
    if (state.spindle_converter_hours && state.spindle_motor_hours)
      kept.spindle =
          schema::PlantStateFile::Spindle{*state.spindle_converter_hours, *state.spindle_motor_hours};
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    config::replace_file(path, schema::plant_state_json(kept));
    return true;
  } catch (...) {
    return false;
  }
}

PlantState plant_state_of(EmulatedCell& cell) {
  PlantState state;
  if (auto* scu = cell.scu())
    for (int a = 1; a <= scu::kActuatorCount; ++a)
      if (scu->has_actuator(a))
        state.actuators[static_cast<std::size_t>(a - 1)] =
            PlantState::Actuator{scu->actuator(a).position_mm(), scu->initialised(a)};
  if (auto* spindle = cell.spindle()) {
    state.spindle_converter_hours = spindle->converter_hours();
    state.spindle_motor_hours = spindle->motor_hours();
  }
  return state;
}

PlantState power_cycled(PlantState state) {
  for (auto& a : state.actuators)
    if (a) a->initialised = false;
  return state;
}

void start_from(emulation::EmulatorSetup& setup, const PlantState& state) {
  if (setup.scu)
    for (std::size_t i = 0; i < state.actuators.size(); ++i) {
      auto& act = setup.scu->actuators[i];
      if (!act.present || !state.actuators[i]) continue;
      // Within the stroke as configured now (a shorter stroke since: the rod at its end).
      act.physics.start_position_mm = std::clamp(state.actuators[i]->position_mm, 0.0, act.physics.stroke_mm);
      setup.scu->initialised[i] = state.actuators[i]->initialised;
    }
  if (setup.spindle && state.spindle_converter_hours && state.spindle_motor_hours) {
    setup.spindle->converter_hours = *state.spindle_converter_hours;
    setup.spindle->motor_hours = *state.spindle_motor_hours;
  }
}

}  // namespace cellctl::runtime

#include "runtime/plant_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "config/config_edit.hpp"
#include "runtime/emulated_cell.hpp"

namespace cellctl::runtime {

PlantState load_plant_state(const std::filesystem::path& path) {
  PlantState state;
  std::ifstream in(path);
  if (!in) return state;
  try {
    const auto j = nlohmann::json::parse(in);
    for (const auto& a : j.at("scu_actuators")) {
      const int index = a.at("actuator").get<int>();
      if (index < 1 || index > scu::kActuatorCount) throw std::out_of_range("actuator out of range");
      state.actuators[static_cast<std::size_t>(index - 1)] =
          PlantState::Actuator{a.at("position_mm").get<double>(), a.at("initialised").get<bool>()};
    }
    if (const auto s = j.find("spindle"); s != j.end()) {
      state.spindle_converter_hours = s->at("converter_hours").get<double>();
      state.spindle_motor_hours = s->at("motor_hours").get<double>();
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format(
        "{}: not the emulated plant's state ({}); delete it to start the emulators as after power-up",
        path.string(), e.what()));
  }
  return state;
}

bool save_plant_state(const std::filesystem::path& path, const PlantState& state) noexcept {
  try {
    nlohmann::json j;
    j["what"] = "the emulated plant between dry runs (cellctl); delete to start as after power-up";
    j["scu_actuators"] = nlohmann::json::array();
    for (std::size_t i = 0; i < state.actuators.size(); ++i)
      if (const auto& a = state.actuators[i])
        j["scu_actuators"].push_back(
            {{"actuator", i + 1}, {"position_mm", a->position_mm}, {"initialised", a->initialised}});
    if (state.spindle_converter_hours && state.spindle_motor_hours)
      j["spindle"] = {{"converter_hours", *state.spindle_converter_hours},
                      {"motor_hours", *state.spindle_motor_hours}};
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    config::replace_file(path, j.dump(2) + "\n");
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

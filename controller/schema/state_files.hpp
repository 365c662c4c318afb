#pragma once
// The files cellctl keeps between runs, typed, and their JSON: the home record (<state_dir>/home.json:
// what was homed, with which config) and the emulated plant's state (<state_dir>/plant.dry-run.json:
// where the emulators' rods stand between dry runs). Who reads and writes them, and when, is
// runtime's (runtime/home_record_file.hpp, runtime/plant_state.hpp); their text is made and read here.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace cellctl::schema {

// {"config_sha256","config","axes":{"<name>":{"strategy","encoder_mm" (null: not measured),"scu_mm",
//  "unix_time","time" (UTC, for people)}}}
struct HomeRecordFile {
  std::string config_sha256;
  std::string config;  // the config file it was made with, for people
  struct Axis {
    std::string name;
    std::string strategy;  // config::to_string(HomingStrategy)
    std::optional<double> encoder_mm;
    double scu_mm = 0.0;
    std::int64_t unix_time = 0;
  };
  std::vector<Axis> axes;  // the homed ones
};

[[nodiscard]] std::string home_record_json(const HomeRecordFile& record);
// The record, or why the text is none (in the JSON reader's words).
[[nodiscard]] std::variant<HomeRecordFile, std::string> read_home_record_json(std::string_view text);

// {"what","scu_actuators":[{"actuator" (1-based),"position_mm","initialised"}],
//  "spindle":{"converter_hours","motor_hours"}}
struct PlantStateFile {
  struct Actuator {
    int actuator = 0;
    double position_mm = 0.0;
    bool initialised = false;
  };
  std::vector<Actuator> scu_actuators;
  struct Spindle {
    double converter_hours = 0.0;
    double motor_hours = 0.0;
  };
  std::optional<Spindle> spindle;
};

[[nodiscard]] std::string plant_state_json(const PlantStateFile& state);
[[nodiscard]] std::variant<PlantStateFile, std::string> read_plant_state_json(std::string_view text);

}  // namespace cellctl::schema

#include "schema/state_files.hpp"

#include <ctime>
#include <nlohmann/json.hpp>

namespace cellctl::schema {
namespace {

using nlohmann::json;

std::string utc(std::int64_t unix_time) {
  const auto t = static_cast<std::time_t>(unix_time);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

std::string home_record_json(const HomeRecordFile& record) {
  json j;
  j["config_sha256"] = record.config_sha256;
  j["config"] = record.config;
  j["axes"] = json::object();
  for (const auto& a : record.axes)
    j["axes"][a.name] = {{"strategy", a.strategy},
                         {"encoder_mm", a.encoder_mm ? json(*a.encoder_mm) : json(nullptr)},
                         {"scu_mm", a.scu_mm},
                         {"unix_time", a.unix_time},
                         {"time", utc(a.unix_time)}};
  return j.dump(2) + "\n";
}

std::variant<HomeRecordFile, std::string> read_home_record_json(std::string_view text) {
  try {
    const auto j = json::parse(text);
    HomeRecordFile r;
    r.config_sha256 = j.at("config_sha256").get<std::string>();
    r.config = j.value("config", std::string());
    for (const auto& [name, a] : j.at("axes").items()) {
      HomeRecordFile::Axis axis;
      axis.name = name;
      axis.strategy = a.at("strategy").get<std::string>();
      if (a.contains("encoder_mm") && !a.at("encoder_mm").is_null())
        axis.encoder_mm = a.at("encoder_mm").get<double>();
      axis.scu_mm = a.at("scu_mm").get<double>();
      axis.unix_time = a.value("unix_time", std::int64_t{0});
      r.axes.push_back(std::move(axis));
    }
    return r;
  } catch (const json::exception& e) {
    return std::string(e.what());
  }
}

std::string plant_state_json(const PlantStateFile& state) {
  json j;
  j["what"] = "the emulated plant between dry runs (cellctl); delete to start as after power-up";
  j["scu_actuators"] = json::array();
  for (const auto& a : state.scu_actuators)
    j["scu_actuators"].push_back(
        {{"actuator", a.actuator}, {"position_mm", a.position_mm}, {"initialised", a.initialised}});
  if (state.spindle)
    j["spindle"] = {{"converter_hours", state.spindle->converter_hours},
                    {"motor_hours", state.spindle->motor_hours}};
  return j.dump(2) + "\n";
}

std::variant<PlantStateFile, std::string> read_plant_state_json(std::string_view text) {
  try {
    const auto j = json::parse(text);
    PlantStateFile state;
    for (const auto& a : j.at("scu_actuators"))
      state.scu_actuators.push_back(
          {a.at("actuator").get<int>(), a.at("position_mm").get<double>(), a.at("initialised").get<bool>()});
    if (const auto s = j.find("spindle"); s != j.end())
      state.spindle =
          PlantStateFile::Spindle{s->at("converter_hours").get<double>(), s->at("motor_hours").get<double>()};
    return state;
  } catch (const json::exception& e) {
    return std::string(e.what());
  }
}

}  // namespace cellctl::schema

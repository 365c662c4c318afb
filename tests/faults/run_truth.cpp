#include "faults/run_truth.hpp"

#include <fstream>

namespace cellctl::faults {

std::string_view to_string(Safe s) noexcept {
  constexpr std::string_view names[] = {"observed", "bounded", "unknown"};
  return names[static_cast<std::size_t>(s)];
}

DeviceSafety device_safety(const nlohmann::json& summary) {
  DeviceSafety out;
  if (!summary.is_object()) return out;
  const auto devices = summary.find("devices");
  if (devices == summary.end() || !devices->is_object()) return out;
  out.present = true;
  for (const auto d : kDevices) {
    const auto dev = devices->find(std::string(cell::to_string(d)));
    if (dev == devices->end() || !dev->is_object()) continue;
    const auto i = static_cast<std::size_t>(d);
    const auto word = dev->value("safe", std::string());
    for (const auto s : {Safe::observed, Safe::bounded, Safe::unknown})
      if (word == to_string(s)) out.safe[i] = s;
    out.evidence[i] = dev->value("evidence", std::string());
  }
  return out;
}

std::vector<nlohmann::json> read_journal(const std::filesystem::path& file) {
  std::vector<nlohmann::json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded()) out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json summary_of(const std::vector<nlohmann::json>& journal) {
  if (journal.empty() || journal.back().value("event", "") != "summary") return nullptr;
  return journal.back();
}

bool spindle_turning(runtime::EmulatedCell& plant) {
  return plant.spindle() && !plant.spindle()->motor().at_rest();
}

bool axes_moving(runtime::EmulatedCell& plant) {
  auto* scu = plant.scu();
  if (!scu) return false;
  for (int a = 1; a <= scu::kActuatorCount; ++a)
    if (scu->has_actuator(a) && scu->actuator(a).moving()) return true;
  return false;
}

}  // namespace cellctl::faults

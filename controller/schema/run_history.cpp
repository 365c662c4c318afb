#include "schema/run_history.hpp"

#include <nlohmann/json.hpp>

namespace cellctl::schema {
namespace {

using nlohmann::json;

// The line as a JSON object whose "event" is `event`; null otherwise.
json line_of(std::string_view line, std::string_view event) {
  auto j = json::parse(line, nullptr, false);
  if (!j.is_object()) return nullptr;
  const auto it = j.find("event");
  if (it == j.end() || !it->is_string() || it->get_ref<const std::string&>() != event) return nullptr;
  return j;
}

}  // namespace

std::string run_history_json(const RunHistory& history) {
  json runs = json::array();
  for (const auto& r : history.runs) {
    json run{{"run", r.run}, {"outcome", nullptr}, {"plot", r.plot}};
    if (r.recipe) run["recipe"] = *r.recipe;
    if (r.ended) {
      run["outcome"] = r.ended->outcome;
      run["duration_s"] = r.ended->duration_s;
      run["devices"] = json::array();
      for (const auto& d : r.ended->devices)
        run["devices"].push_back({{"name", d.device}, {"safe", d.safe}, {"evidence", d.evidence}});
    }
    runs.push_back(std::move(run));
  }
  return json{{"runs", std::move(runs)}, {"more", history.more}}.dump();
}

std::optional<std::string> header_recipe(std::string_view line) {
  try {
    const auto j = line_of(line, "record");
    if (j.is_null()) return std::nullopt;
    return j.value("recipe", std::string());
  } catch (const json::exception&) {
    return std::nullopt;  // a key of another type than this version writes
  }
}

std::optional<RunEntry::Ended> summary_end(std::string_view line) {
  try {
    const auto j = line_of(line, "summary");
    if (j.is_null()) return std::nullopt;
    RunEntry::Ended e;
    e.outcome = j.value("outcome", std::string());
    e.duration_s = j.value("duration_s", 0.0);
    if (const auto it = j.find("devices"); it != j.end() && it->is_object())
      for (const auto& [name, d] : it->items())
        if (d.is_object())
          e.devices.push_back({name, d.value("safe", std::string()), d.value("evidence", std::string())});
    return e;
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

}  // namespace cellctl::schema

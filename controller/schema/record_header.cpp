#include "schema/record_header.hpp"

#include <nlohmann/json.hpp>

#include "schema/json_records.hpp"

namespace cellctl::schema {
namespace {

using nlohmann::json;

void put(json& j, const char* key, const std::optional<std::string>& value) {
  if (value) j[key] = *value;
}

std::optional<std::string> text_at(const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_string()) return std::nullopt;
  return it->get<std::string>();
}

}  // namespace

std::string header_line(const RecordHeader& h) {
  json j;
  j["t"] = 0.0;
  j["event"] = "record";
  put(j, "recipe_file", h.recipe_file);
  put(j, "recipe_sha256", h.recipe_sha256);
  put(j, "recipe", h.recipe);
  put(j, "recipe_version", h.recipe_version);
  put(j, "config_file", h.config_file);
  put(j, "config_sha256", h.config_sha256);
  put(j, "cell", h.cell);
  put(j, "cellctl", h.cellctl);
  put(j, "mode", h.mode);
  j["ports"] = h.ports;
  put(j, "host", h.host);
  put(j, "started_utc", h.started_utc);
  j["sample_s"] = h.sample_s;
  j["position_unit"] = "mm";
  j["spindle_unit"] = "Hz";
  j["axes"] = json::array();
  for (const auto& a : h.axes) {
    json axis{{"measured", a.measured}};
    put(axis, "name", a.name);
    j["axes"].push_back(axis);
  }
  j["steps"] = json::array();
  for (std::size_t i = 0; i < h.steps.size(); ++i) {
    const auto& s = h.steps[i];
    json step{{"step", i + 1}, {"label", s.label}, {"kind", s.kind}};
    if (s.planned_s) step["planned_s"] = *s.planned_s;
    j["steps"].push_back(step);
  }
  return j.dump();
}

RecordHeader header_of(const json& j) {
  RecordHeader h;
  h.recipe_file = text_at(j, "recipe_file");
  h.recipe_sha256 = text_at(j, "recipe_sha256");
  h.recipe = text_at(j, "recipe");
  h.recipe_version = text_at(j, "recipe_version");
  h.config_file = text_at(j, "config_file");
  h.config_sha256 = text_at(j, "config_sha256");
  h.cell = text_at(j, "cell");
  h.cellctl = text_at(j, "cellctl");
  h.mode = text_at(j, "mode");
  h.host = text_at(j, "host");
  h.started_utc = text_at(j, "started_utc");
  if (const auto it = j.find("ports"); it != j.end() && it->is_array())
    for (const auto& p : *it)
      if (p.is_string()) h.ports.push_back(p.get<std::string>());
  h.sample_s = j.value("sample_s", h.sample_s);
  if (const auto it = j.find("axes"); it != j.end() && it->is_array())
    for (const auto& a : *it) h.axes.push_back({text_at(a, "name"), a.value("measured", false)});
  if (const auto it = j.find("steps"); it != j.end() && it->is_array())
    for (const auto& s : *it) {
      RecordHeader::Step step{s.value("label", ""), s.value("kind", ""), std::nullopt};
      if (const auto p = s.find("planned_s"); p != s.end()) step.planned_s = p->get<double>();
      h.steps.push_back(std::move(step));
    }
  return h;
}

}  // namespace cellctl::schema

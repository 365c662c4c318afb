#include "schema/plant_tags.hpp"

#include <nlohmann/json.hpp>

namespace cellctl::schema {
namespace {

using nlohmann::json;

json stop_reason_json(const StopReason& r) {
  json j{{"t", r.t}, {"text", r.text}};
  switch (r.by) {
    case StopReason::By::state:
      j["state"] = r.state;
      break;
    case StopReason::By::step:
      j["step"] = r.step;
      break;
    case StopReason::By::command:
      j["command"] = r.command;
      j["source"] = r.source;
      break;
    case StopReason::By::fault:
      j["fault"] = r.fault;
      j["category"] = r.category;
      break;
  }
  return j;
}

}  // namespace

std::string state_payload(const StateTag& tag) {
  json j{{"StateCurrent", tag.state_current}, {"state", tag.state}, {"t", tag.t}};
  if (!tag.reason.empty()) j["reason"] = tag.reason;
  return j.dump();
}

std::string mode_payload(const ModeTag& tag) {
  return json{{"UnitModeCurrent", tag.unit_mode_current}, {"mode", tag.mode}, {"recipe", tag.recipe}}.dump();
}

std::string admin_payload(const AdminTag& tag) {
  json faults = json::array();
  for (const auto& f : tag.active_faults) {
    json fault{{"rule", f.rule}, {"category", f.category}, {"text", f.text}, {"t", f.t}};
    if (f.remedy) fault["remedy"] = *f.remedy;
    faults.push_back(std::move(fault));
  }
  return json{{"runs", tag.runs},
              {"steps_done", tag.steps_done},
              {"steps_failed", tag.steps_failed},
              {"faults", tag.faults},
              {"ProdProcessedCount", tag.processed},
              {"ProdDefectiveCount", tag.defective},
              {"StopReason", tag.stop_reason ? stop_reason_json(*tag.stop_reason) : json(nullptr)},
              {"active_faults", faults}}
      .dump();
}

std::string status_payload(const StatusTag& tag) {
  json j;
  j["t"] = tag.t;
  j["state"] = tag.state;
  j["step"] = tag.step;
  j["steps"] = tag.steps;
  j["label"] = tag.label;
  j["progress"] = tag.progress;
  json axes = json::array();
  for (const auto& a : tag.axes) {
    json axis{{"name", a.name}};
    if (a.planned_mm) axis["planned_mm"] = *a.planned_mm;
    if (a.measured_mm) axis["measured_mm"] = *a.measured_mm;
    axes.push_back(std::move(axis));
  }
  j["axes"] = axes;
  if (tag.sampled) {
    j["encoder_mm"] = tag.sampled->encoder_mm;
    j["spindle"] = {{"set_hz", tag.sampled->spindle_set_hz}, {"actual_hz", tag.sampled->spindle_hz}};
    j["CurMachSpeed"] = tag.sampled->spindle_hz;
  }
  j["jitter_max_us"] = tag.jitter_max_us;
  if (tag.link)
    j["link"] = {{"reconnects", tag.link->reconnects},
                 {"dropped_status", tag.link->dropped_status},
                 {"dropped_events", tag.link->dropped_events},
                 {"ignored_retained", tag.link->ignored_retained},
                 {"mqtt", tag.link->mqtt}};
  return j.dump();
}

std::string online_payload(const std::string& client_id, const std::string& cell) {
  return json{{"online", true}, {"client_id", client_id}, {"cell", cell}}.dump();
}

std::string offline_payload(const std::string& client_id, const std::string& reason) {
  return json{{"online", false}, {"client_id", client_id}, {"reason", reason}}.dump();
}

std::string cell_payload(const std::string& cell) {
  return json{{"cell", cell}}.dump();
}

}  // namespace cellctl::schema

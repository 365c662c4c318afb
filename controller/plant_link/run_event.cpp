#include "plant_link/run_event.hpp"

#include <string>

namespace cellctl::plant_link {
namespace {

journal::Text text_of(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_string()) return {};
  return journal::Text::format("{}", it->get_ref<const std::string&>());
}

void floats_of(const nlohmann::json& j, const char* key, std::array<float, journal::kMaxAxes>& out,
               std::uint8_t& n) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_array()) return;
  n = 0;
  for (const auto& v : *it) {
    if (n == out.size() || !v.is_number()) break;
    out[n++] = v.get<float>();
  }
}

}  // namespace

std::optional<RunEvent> run_event_of(const nlohmann::json& j) {
  using Kind = RunEvent::Kind;
  const auto ev = j.value("event", std::string());
  RunEvent e;
  e.t = j.value("t", 0.0);
  if (ev == "run_started") {
    e.kind = Kind::run_started;
    e.name = text_of(j, "recipe");
    e.other = text_of(j, "mode");
    e.step = j.value("steps", 0u);
  } else if (ev == "state") {
    e.kind = Kind::state;
    e.name = text_of(j, "to");
    e.other = text_of(j, "from");
    e.text = text_of(j, "reason");
  } else if (ev == "step_started" || ev == "step_done" || ev == "step_failed") {
    e.kind = ev == "step_started" ? Kind::step_started
             : ev == "step_done"  ? Kind::step_done
                                  : Kind::step_failed;
    e.step = j.value("step", 0u);
    e.name = text_of(j, "label");
    e.text = text_of(j, "detail");
  } else if (ev == "command") {
    e.kind = Kind::command;
    e.name = text_of(j, "command");
    e.other = text_of(j, "source");
  } else if (ev == "fault") {
    e.kind = Kind::fault;
    e.name = text_of(j, "rule");
    e.category = static_cast<std::uint8_t>(j.value("category", 1));
    e.text = text_of(j, "detail");
  } else if (ev == "fault_cleared") {
    e.kind = Kind::fault_cleared;
    e.name = text_of(j, "rule");
  } else if (ev == "sample") {
    e.kind = Kind::sample;
    floats_of(j, "planned_mm", e.planned_mm, e.axes);
    std::uint8_t n = 0;
    floats_of(j, "scu_mm", e.scu_mm, n);
    e.encoder_mm = j.value("encoder_mm", 0.0f);
    e.spindle_set_hz = j.value("spindle_set_hz", 0.0f);
    e.spindle_hz = j.value("spindle_hz", 0.0f);
  } else if (ev == "note") {
    e.kind = Kind::note;
    e.text = text_of(j, "text");
  } else if (ev == "run_ended") {
    e.kind = Kind::run_ended;
    e.name = text_of(j, "outcome");
  } else {
    return std::nullopt;
  }
  return e;
}

}  // namespace cellctl::plant_link

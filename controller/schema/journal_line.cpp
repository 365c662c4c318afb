#include "schema/journal_line.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "schema/json_text.hpp"

namespace cellctl::schema {
namespace {

using nlohmann::json;

json axes_array(const std::array<float, journal::kMaxAxes>& v, std::uint8_t n) {
  json a = json::array();
  for (std::uint8_t i = 0; i < n; ++i) a.push_back(recorded_value(v[i]));
  return a;
}

struct Fill {
  json& j;
  void operator()(const journal::RunStarted& e) const {
    j["event"] = "run_started";
    j["recipe"] = str(e.recipe);
    j["cell"] = str(e.cell);
    j["mode"] = str(e.mode);
    j["steps"] = e.steps;
  }
  void operator()(const journal::StateChanged& e) const {
    j["event"] = "state";
    j["from"] = str(e.from);
    j["to"] = str(e.to);
    if (e.reason.size) j["reason"] = str(e.reason.view());
  }
  void operator()(const journal::StepStarted& e) const {
    j["event"] = "step_started";
    j["step"] = e.index + 1;
    j["label"] = str(e.label);
  }
  void operator()(const journal::StepEnded& e) const {
    j["event"] = e.ok ? "step_done" : "step_failed";
    j["step"] = e.index + 1;
    j["label"] = str(e.label);
    if (e.detail.size) j["detail"] = str(e.detail.view());
  }
  void operator()(const journal::Command& e) const {
    j["event"] = "command";
    j["command"] = str(e.name);
    j["source"] = str(e.source.view());
  }
  void operator()(const journal::Fault& e) const {
    j["event"] = "fault";
    j["rule"] = str(e.rule);
    j["category"] = e.category;
    j["detail"] = str(e.detail.view());
  }
  void operator()(const journal::FaultCleared& e) const {
    j["event"] = "fault_cleared";
    j["rule"] = str(e.rule);
  }
  void operator()(const journal::Sample& e) const {
    j["event"] = "sample";
    j["planned_mm"] = axes_array(e.planned_mm, e.axes);
    j["scu_mm"] = axes_array(e.scu_mm, e.axes);
    j["encoder_mm"] = recorded_value(e.encoder_mm);
    j["encoder_mm_s"] = recorded_value(e.encoder_mm_s);
    j["spindle_set_hz"] = recorded_value(e.spindle_set_hz);
    j["spindle_hz"] = recorded_value(e.spindle_actual_hz);
  }
  void operator()(const journal::Note& e) const {
    j["event"] = "note";
    j["text"] = str(e.text.view());
  }
  void operator()(const journal::InjectedFault& e) const {
    j["event"] = e.ended ? "fault_injection_ended" : "fault_injected";
    j["device"] = str(e.device);
    j["kind"] = str(e.kind);
    j["spec"] = str(e.spec);
    j["what"] = str(e.what);
    if (e.still_active) j["still_active"] = true;
  }
  void operator()(const journal::RunEnded& e) const {
    j["event"] = "run_ended";
    j["outcome"] = str(e.outcome);
  }
};

}  // namespace

double recorded_time(double t) noexcept {
  return std::round(t * 1e6) / 1e6;
}

double recorded_value(float v) noexcept {
  return std::round(static_cast<double>(v) * 1e4) / 1e4;
}

SamplePoint sample_point(double t, const journal::Sample& s) {
  SamplePoint p;
  p.t = recorded_time(t);
  for (std::uint8_t i = 0; i < s.axes && i < journal::kMaxAxes; ++i) {
    p.planned_mm.push_back(recorded_value(s.planned_mm[i]));
    p.scu_mm.push_back(recorded_value(s.scu_mm[i]));
  }
  p.encoder_mm = recorded_value(s.encoder_mm);
  p.encoder_mm_s = recorded_value(s.encoder_mm_s);
  p.spindle_set_hz = recorded_value(s.spindle_set_hz);
  p.spindle_hz = recorded_value(s.spindle_actual_hz);
  return p;
}

std::string event_line(const journal::Event& e) {
  json j;
  j["t"] = recorded_time(e.t);
  std::visit(Fill{j}, e.payload);
  return j.dump();
}

std::string note_line(double t, std::string_view text) {
  return json{{"t", recorded_time(t)}, {"event", "note"}, {"text", str(text)}}.dump();
}

}  // namespace cellctl::schema

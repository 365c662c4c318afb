#include "journal/event_json.hpp"

#include <cmath>
#include <string>

namespace cellctl::journal {
namespace {

using nlohmann::json;

std::string str(std::string_view s) {
  return std::string(s);
}

// Samples are floats: written as the nearest 0.1 µm (0.0001 Hz), not as the float's binary
// expansion (12.300000190734863), which no reader wants and which triples the file.
double tidy(float v) {
  return std::round(static_cast<double>(v) * 1e4) / 1e4;
}

json axes_array(const std::array<float, kMaxAxes>& v, std::uint8_t n) {
  json a = json::array();
  for (std::uint8_t i = 0; i < n; ++i) a.push_back(tidy(v[i]));
  return a;
}

struct Fill {
  json& j;
  void operator()(const RunStarted& e) const {
    j["event"] = "run_started";
    j["recipe"] = str(e.recipe);
    j["cell"] = str(e.cell);
    j["mode"] = str(e.mode);
    j["steps"] = e.steps;
  }
  void operator()(const StateChanged& e) const {
    j["event"] = "state";
    j["from"] = str(e.from);
    j["to"] = str(e.to);
    if (e.reason.size) j["reason"] = str(e.reason.view());
  }
  void operator()(const StepStarted& e) const {
    j["event"] = "step_started";
    j["step"] = e.index + 1;
    j["label"] = str(e.label);
  }
  void operator()(const StepEnded& e) const {
    j["event"] = e.ok ? "step_done" : "step_failed";
    j["step"] = e.index + 1;
    j["label"] = str(e.label);
    if (e.detail.size) j["detail"] = str(e.detail.view());
  }
  void operator()(const Command& e) const {
    j["event"] = "command";
    j["command"] = str(e.name);
    j["source"] = str(e.source.view());
  }
  void operator()(const Fault& e) const {
    j["event"] = "fault";
    j["rule"] = str(e.rule);
    j["category"] = e.category;
    j["detail"] = str(e.detail.view());
  }
  void operator()(const FaultCleared& e) const {
    j["event"] = "fault_cleared";
    j["rule"] = str(e.rule);
  }
  void operator()(const Sample& e) const {
    j["event"] = "sample";
    j["planned_mm"] = axes_array(e.planned_mm, e.axes);
    j["scu_mm"] = axes_array(e.scu_mm, e.axes);
    j["encoder_mm"] = tidy(e.encoder_mm);
    j["encoder_mm_s"] = tidy(e.encoder_mm_s);
    j["spindle_set_hz"] = tidy(e.spindle_set_hz);
    j["spindle_hz"] = tidy(e.spindle_actual_hz);
  }
  void operator()(const Note& e) const {
    j["event"] = "note";
    j["text"] = str(e.text.view());
  }
  void operator()(const InjectedFault& e) const {
    j["event"] = e.ended ? "fault_injection_ended" : "fault_injected";
    j["device"] = str(e.device);
    j["kind"] = str(e.kind);
    j["spec"] = str(e.spec);
    j["what"] = str(e.what);
    if (e.still_active) j["still_active"] = true;
  }
  void operator()(const RunEnded& e) const {
    j["event"] = "run_ended";
    j["outcome"] = str(e.outcome);
  }
};

}  // namespace

json to_json(const Event& e) {
  json j;
  j["t"] = std::round(e.t * 1e6) / 1e6;
  std::visit(Fill{j}, e.payload);
  return j;
}

}  // namespace cellctl::journal

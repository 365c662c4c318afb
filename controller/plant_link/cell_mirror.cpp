#include "plant_link/cell_mirror.hpp"

#include <algorithm>
#include <string_view>

#include "plant_link/packml_tags.hpp"

namespace cellctl::plant_link {
namespace {

std::string str(const journal::Text& t) {
  return std::string(t.view());
}

}  // namespace

CellMirror::CellMirror(const config::CellCore& cell, std::string run_mode) : run_mode_(std::move(run_mode)) {
  for (const auto& a : cell.axes) axes_.push_back(a.name);
}

Changed CellMirror::apply(const RunEvent& e) {
  using Kind = RunEvent::Kind;
  Changed c;
  switch (e.kind) {
    case Kind::run_started:
      ++runs_;
      recipe_ = str(e.name);
      steps_ = e.step;
      step_ = 0;
      run_mode_ = str(e.other);
      active_faults_.clear();
      stop_reason_ = nullptr;  // each job's own: an earlier job's stop is no reason for this one
      c.admin = c.mode = true;
      break;
    case Kind::state:
      state_ = str(e.name);
      state_t_ = e.t;
      state_reason_ = str(e.text);
      c.state = true;
      if (state_ == "Complete") {
        ++processed_;
        c.admin = true;
      }
      if ((state_ == "Stopping" || state_ == "Aborting" || state_ == "Holding") && !state_reason_.empty() &&
          stop_reason_.is_null()) {
        stop_reason_ = {{"t", e.t}, {"state", state_}, {"text", state_reason_}};
        c.admin = true;
      }
      break;
    case Kind::step_started:
      step_ = e.step;
      step_label_ = str(e.name);
      break;
    case Kind::step_done:
      ++steps_done_;
      c.admin = true;
      break;
    case Kind::step_failed:
      ++steps_failed_;
      stop_reason_ = {
          {"t", e.t},
          {"step", e.step},
          {"text", "step " + std::to_string(e.step) + " (" + str(e.name) + ") failed: " + str(e.text)}};
      c.admin = true;
      break;
    case Kind::command:
      if (e.name.view() == "stop" || e.name.view() == "abort" || e.name.view() == "hold") {
        stop_reason_ = {{"t", e.t},
                        {"command", str(e.name)},
                        {"source", str(e.other)},
                        {"text", str(e.name) + " commanded by " + str(e.other)}};
        c.admin = true;
      }
      break;
    case Kind::fault:
      ++faults_;
      active_faults_.push_back(
          {{"rule", str(e.name)}, {"category", e.category}, {"text", str(e.text)}, {"t", e.t}});
      stop_reason_ = {{"t", e.t},
                      {"fault", str(e.name)},
                      {"category", e.category},
                      {"text", str(e.name) + ": " + str(e.text)}};
      c.admin = true;
      break;
    case Kind::fault_cleared:
      std::erase_if(active_faults_, [&](const nlohmann::json& f) { return f["rule"] == str(e.name); });
      c.admin = true;
      break;
    case Kind::sample:
      sample_ = e;
      has_sample_ = true;
      break;
    case Kind::note:
    case Kind::run_ended:
      break;
  }
  return c;
}

nlohmann::json CellMirror::state_tag() const {
  nlohmann::json j{{"StateCurrent", packml_state_number(state_)}, {"state", state_}, {"t", state_t_}};
  if (!state_reason_.empty()) j["reason"] = state_reason_;
  return j;
}

nlohmann::json CellMirror::mode_tag() const {
  const auto m = unit_mode(run_mode_);
  return {{"UnitModeCurrent", m.number}, {"mode", std::string(m.name)}, {"recipe", recipe_}};
}

nlohmann::json CellMirror::admin_tag() const {
  return {{"runs", runs_},
          {"steps_done", steps_done_},
          {"steps_failed", steps_failed_},
          {"faults", faults_},
          {"ProdProcessedCount", processed_},
          {"StopReason", stop_reason_},
          {"active_faults", active_faults_}};
}

nlohmann::json CellMirror::status_tag(const LiveStatus& live) const {
  nlohmann::json j;
  j["t"] = live.known ? live.t : state_t_;
  j["state"] = state_;
  j["step"] = live.known ? live.step : step_;
  j["steps"] = live.known ? live.steps : steps_;
  j["label"] = live.known ? live.label : step_label_;
  // The fraction of steps done: the current one counts once it is over (all of them at Complete).
  const auto steps = live.known ? live.steps : steps_;
  const auto step = live.known ? live.step : step_;
  j["progress"] = state_ == "Complete" ? 1.0
                  : steps              ? static_cast<double>(step > 0 ? step - 1 : 0) / steps
                                       : 0.0;
  nlohmann::json axes = nlohmann::json::array();
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    nlohmann::json a{{"name", axes_[i]}};
    if (has_sample_ && i < sample_.axes) {
      a["planned_mm"] = sample_.planned_mm[i];
      a["measured_mm"] = sample_.scu_mm[i];
    }
    axes.push_back(a);
  }
  j["axes"] = axes;
  if (has_sample_) {
    j["encoder_mm"] = sample_.encoder_mm;
    j["spindle"] = {{"set_hz", sample_.spindle_set_hz}, {"actual_hz", sample_.spindle_hz}};
    // PackML Status.CurMachSpeed: the spindle's actual frequency is this cell's machine speed.
    j["CurMachSpeed"] = sample_.spindle_hz;
  }
  j["jitter_max_us"] = live.jitter_max_us;
  return j;
}

}  // namespace cellctl::plant_link

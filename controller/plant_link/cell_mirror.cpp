#include "plant_link/cell_mirror.hpp"

#include <algorithm>
#include <string_view>

#include "plant_link/packml_tags.hpp"
#include "plant_link/tag_resolution.hpp"

namespace cellctl::plant_link {
namespace {

std::string str(const journal::Text& t) {
  return std::string(t.view());
}

}  // namespace

CellMirror::CellMirror(const config::CellCore& cell, std::string run_mode) : run_mode_(std::move(run_mode)) {
  for (const auto& a : cell.axes) axes_.push_back({a.name, position_decimals(a)});
}

Changed CellMirror::apply(const RunEvent& e) {
  using Kind = RunEvent::Kind;
  using By = schema::StopReason::By;
  Changed c;
  switch (e.kind) {
    case Kind::run_started:
      ++admin_.runs;
      recipe_ = str(e.name);
      producing_ = e.text.view() == "recipe";
      steps_ = e.step;
      step_ = 0;
      run_mode_ = str(e.other);
      admin_.active_faults.clear();
      admin_.stop_reason.reset();  // each job's own: an earlier job's stop is no reason for this one
      c.admin = c.mode = true;
      break;
    case Kind::state:
      state_ = str(e.name);
      state_t_ = e.t;
      state_reason_ = str(e.text);
      c.state = true;
      // A recipe's run ends once, in one of the three; a homing or a Teach-In makes nothing. The arbiter's
      // own Stopped and Aborted between jobs (no run) are not runs either.
      if (producing_ && (state_ == "Complete" || state_ == "Stopped" || state_ == "Aborted")) {
        ++(state_ == "Complete" ? admin_.processed : admin_.defective);
        producing_ = false;
        c.admin = true;
      }
      if ((state_ == "Stopping" || state_ == "Aborting" || state_ == "Holding") && !state_reason_.empty() &&
          !admin_.stop_reason) {
        admin_.stop_reason = schema::StopReason{By::state, e.t, state_reason_, state_, 0, {}, {}, {}, 0};
        c.admin = true;
      }
      break;
    case Kind::step_started:
      step_ = e.step;
      step_label_ = str(e.name);
      break;
    case Kind::step_done:
      ++admin_.steps_done;
      c.admin = true;
      break;
    case Kind::step_failed:
      ++admin_.steps_failed;
      admin_.stop_reason = schema::StopReason{
          By::step,
          e.t,
          "step " + std::to_string(e.step) + " (" + str(e.name) + ") failed: " + str(e.text),
          {},
          e.step,
          {},
          {},
          {},
          0};
      c.admin = true;
      break;
    case Kind::command:
      if (e.name.view() == "stop" || e.name.view() == "abort" || e.name.view() == "hold") {
        admin_.stop_reason = schema::StopReason{
            By::command, e.t, str(e.name) + " commanded by " + str(e.other), {}, 0, str(e.name), str(e.other),
            {},          0};
        c.admin = true;
      }
      break;
    case Kind::fault:
      ++admin_.faults;
      admin_.active_faults.push_back({str(e.name), e.category, str(e.text), e.t, std::nullopt});
      admin_.stop_reason = schema::StopReason{
          By::fault, e.t, str(e.name) + ": " + str(e.text), {}, 0, {}, {}, str(e.name), e.category};
      c.admin = true;
      break;
    case Kind::fault_cleared:
      std::erase_if(admin_.active_faults,
                    [&](const schema::ActiveFault& f) { return f.rule == e.name.view(); });
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

schema::StateTag CellMirror::state_tag() const {
  return {packml_state_number(state_), state_, state_t_, state_reason_};
}

schema::ModeTag CellMirror::mode_tag() const {
  const auto m = unit_mode(run_mode_);
  return {m.number, std::string(m.name), recipe_};
}

schema::StatusTag CellMirror::status_tag(const LiveStatus& live) const {
  schema::StatusTag s;
  s.t = live.known ? live.t : state_t_;
  s.state = state_;
  s.step = live.known ? live.step : step_;
  s.steps = live.known ? live.steps : steps_;
  s.label = live.known ? live.label : step_label_;
  // The fraction of steps done: the current one counts once it is over (all of them at Complete).
  s.progress = to_decimals(state_ == "Complete" ? 1.0
                           : s.steps            ? static_cast<double>(s.step > 0 ? s.step - 1 : 0) / s.steps
                                                : 0.0,
                           kProgressDecimals);
  // The last positions read stay in the status between jobs and in Idle: the cell at rest where the
  // last job left it.
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    schema::StatusTag::Axis a{axes_[i].name, std::nullopt, std::nullopt};
    if (has_sample_ && i < sample_.axes) {
      a.planned_mm = to_decimals(sample_.planned_mm[i], axes_[i].decimals);
      a.measured_mm = to_decimals(sample_.scu_mm[i], axes_[i].decimals);
    }
    s.axes.push_back(std::move(a));
  }
  if (has_sample_)
    s.sampled = schema::StatusTag::Sampled{to_decimals(sample_.encoder_mm, kEncoderDecimals),
                                           to_decimals(sample_.spindle_set_hz, kSpindleDecimals),
                                           to_decimals(sample_.spindle_hz, kSpindleDecimals)};
  s.jitter_max_us = to_decimals(live.jitter_max_us, kJitterDecimals);
  return s;
}

}  // namespace cellctl::plant_link

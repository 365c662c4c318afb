#include "supervisor/supervisor.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "supervisor/cell_sample.hpp"

namespace cellctl::supervisor {
namespace {

// How long a `require: homed` waits for the SCU's first status read after activation.
constexpr double kStatusWaitS = 3.0;

using journal::Text;

bool is_running_state(State s) noexcept {
  return s == State::execute || s == State::unholding || s == State::holding || s == State::held ||
         s == State::completing;
}

// Every device of the cell, up or down, for a start that timed out: "scu up, spindle down, encoder not
// ready" (the encoder is up once it is in data exchange and ready).
Text devices_up(const cell::CellState& s) noexcept {
  Text out;
  for (std::size_t d = 0; d < cell::kMaxDevices; ++d) {
    if (s.devices[d].empty()) continue;
    const char* how = s.links[d].active ? "up" : "down";
    if (d == cell::slot(cell::Device::encoder))
      how = s.encoder.data_exchange ? (s.encoder.ready ? "ready" : "not ready") : "down";
    out = Text::format("{}{}{} {}", out.view(), out.size ? ", " : "", s.devices[d], how);
  }
  return out;
}

}  // namespace

Supervisor::Supervisor(const config::CellCore& cell, const recipe::Recipe& recipe,
                       const recipe::Program& program, journal::EventSink& events, double dt,
                       SupervisorSettings settings)
    : cell_(cell),
      recipe_(recipe),
      program_(program),
      events_(events),
      settings_(settings),
      dt_(dt),
      executor_(cell, recipe.limits, dt, settings.move),
      homing_(cell, events, dt, settings.move),
      record_(settings.home_record ? settings.home_record : &own_record_) {}

double Supervisor::planned_mm(std::size_t axis) const noexcept {
  const auto* ins = current();
  if (ins && std::holds_alternative<recipe::Home>(ins->action)) return homing_.planned_mm(axis);
  if (ins && std::holds_alternative<recipe::TeachIn>(ins->action) && teach_in_)
    return teach_in_->planned_mm(axis);
  return executor_.planned_mm(axis);
}

double Supervisor::step_planned_s() const noexcept {
  return move_started() ? executor_.planned_s() : 0.0;
}

const recipe::Instruction* Supervisor::current() const noexcept {
  return pc_ < program_.instructions.size() ? &program_.instructions[pc_] : nullptr;
}

bool Supervisor::move_started() const noexcept {
  const auto* ins = current();
  return ins && instruction_started_ && std::holds_alternative<recipe::Move>(ins->action);
}

bool Supervisor::command(Command c, std::string_view source, double t) {
  if (const auto why = supervisor::refusal(state_, c); !why.empty()) {
    refusal_ = Text::format("{} is not possible in state {}: {}", to_string(c), to_string(state_), why);
    return false;
  }
  pending_source_ = Text::format("{}", source);
  events_.post(t, journal::Command{to_string(c), pending_source_});
  pending_ = c;
  return true;
}

void Supervisor::enter(State next, double t, const Text& reason) {
  if (next == state_) return;
  events_.post(t, journal::StateChanged{to_string(state_), to_string(next), reason});
  state_ = next;
  state_since_ = t;
}

void Supervisor::clear_motion() noexcept {
  for (auto& a : intents_.axes) a.move = false;
}

bool Supervisor::axes_still(const cell::CellState& s) const noexcept {
  // A move still queued or not yet closed by its RS counts as motion: the SCU's motion bit lags.
  for (std::size_t i = 0; i < s.axis_count; ++i)
    if (s.axes[i].moving || s.axes[i].commanded) return false;
  return true;
}

void Supervisor::apply_demanded(std::optional<config::StopCategory> demanded, double t) {
  // Once the run has ended the cell is at rest and being closed; a later fault changes nothing.
  if (!demanded || is_final(state_)) return;
  switch (*demanded) {
    case config::StopCategory::immediate:
      if (state_ != State::aborting && state_ != State::aborted)
        enter(State::aborting, t, Text::format("stop category 0"));
      break;
    case config::StopCategory::controlled_off:
      if (state_ != State::stopping && state_ != State::stopped && state_ != State::aborting &&
          state_ != State::aborted)
        enter(State::stopping, t, Text::format("stop category 1"));
      break;
    case config::StopCategory::controlled_hold:
      if (state_ == State::execute || state_ == State::unholding || state_ == State::completing)
        enter(State::holding, t, Text::format("stop category 2"));
      else if (state_ == State::starting || state_ == State::idle)
        enter(State::stopping, t, Text::format("stop category 2 before the recipe ran"));
      break;
  }
}

void Supervisor::start_instruction(const cell::CellState& s, double t) {
  const auto& ins = program_.instructions[pc_];
  instruction_started_ = true;
  instruction_t_ = t;
  last_execute_t_ = t;
  if (const auto* move = std::get_if<recipe::Move>(&ins.action)) executor_.start(*move, s, t, move_counter_);
  if (const auto* dwell = std::get_if<recipe::Dwell>(&ins.action)) dwell_left_s_ = dwell->seconds;
  if (const auto* home = std::get_if<recipe::Home>(&ins.action)) homing_.start(home->axes, t, *record_);
  if (const auto* teach = std::get_if<recipe::TeachIn>(&ins.action); teach && settings_.teach_in_port) {
    teach_in_.emplace(cell_, *settings_.teach_in_port, *teach, dt_);
    told_phase_ = teach_in_->phase();
    told_prompt_ = {};
  }
  if (const auto* sp = std::get_if<recipe::Spindle>(&ins.action)) {
    intents_.spindle.run = sp->start;
    if (sp->start) {
      intents_.spindle.frequency_hz = sp->frequency_hz;
      intents_.spindle.clockwise = sp->direction == recipe::SpindleDirection::cw;
    }
  }
  events_.post(t, journal::StepStarted{static_cast<std::uint32_t>(pc_), ins.label});
}

Supervisor::StepStatus Supervisor::run_instruction(const cell::CellState& s, double t) {
  const auto& ins = program_.instructions[pc_];
  const double elapsed = t - instruction_t_;
  const double tol = cell_.limits.spindle_tolerance_hz;

  if (std::holds_alternative<recipe::Move>(ins.action)) {
    const auto status = executor_.step(s, t, intents_, move_counter_);
    if (!executor_.note().empty()) journal::post_note(events_, t, "step {}: {}", pc_ + 1, executor_.note());
    if (status == motion::MoveStatus::failed) failure_ = executor_.reason();
    if (status == motion::MoveStatus::done) corrections_ += executor_.corrections();
    return status == motion::MoveStatus::done     ? StepStatus::done
           : status == motion::MoveStatus::failed ? StepStatus::failed
                                                  : StepStatus::running;
  }
  if (const auto* sp = std::get_if<recipe::Spindle>(&ins.action)) {
    const double want = sp->direction == recipe::SpindleDirection::cw ? sp->frequency_hz : -sp->frequency_hz;
    const bool reached =
        sp->start ? (s.spindle.at_speed && std::abs(s.spindle.actual_hz - want) <= tol) : s.spindle.at_rest;
    if (reached) return StepStatus::done;
    // (From the second cycle on: the first one still sees the state from before the start went out.)
    if (sp->start && s.spindle.start_refused && elapsed > 0.0) {
      failure_ = Text::format(
          "the spindle converter refused the start (its warning/fault {}: `cellctl spindle status` "
          "says why)",
          s.spindle.error_number);
      return StepStatus::failed;
    }
    if (elapsed > recipe_.limits.spindle_timeout_s) {
      failure_ = Text::format("spindle not {} after {:.1f} s (at {:.0f} Hz)",
                              sp->start ? "at speed" : "at rest", elapsed, s.spindle.actual_hz);
      return StepStatus::failed;
    }
    return StepStatus::running;
  }
  if (std::holds_alternative<recipe::Home>(ins.action)) {
    const auto status = homing_.step(s, t, intents_, move_counter_, preset_counter_);
    if (status == routines::HomingStatus::failed) failure_ = homing_.reason();
    return status == routines::HomingStatus::done     ? StepStatus::done
           : status == routines::HomingStatus::failed ? StepStatus::failed
                                                      : StepStatus::running;
  }
  if (std::holds_alternative<recipe::TeachIn>(ins.action)) return run_teach_in(s, t);
  if (std::holds_alternative<recipe::Dwell>(ins.action)) {
    dwell_left_s_ -= t - last_execute_t_;
    last_execute_t_ = t;
    return dwell_left_s_ <= 1e-9 ? StepStatus::done : StepStatus::running;
  }
  if (const auto* w = std::get_if<recipe::Wait>(&ins.action)) {
    bool met = false;
    using C = recipe::Wait::Condition;
    switch (w->condition) {
      case C::position_above:
        met = s.axes[static_cast<std::size_t>(w->axis)].position_mm() > w->threshold_mm;
        break;
      case C::position_below:
        met = s.axes[static_cast<std::size_t>(w->axis)].position_mm() < w->threshold_mm;
        break;
      case C::encoder_ready:
        met = s.encoder.data_exchange && s.encoder.ready;
        break;
      case C::spindle_at_speed:
        met = s.spindle.at_speed;
        break;
      case C::spindle_at_rest:
        met = s.spindle.at_rest;
        break;
    }
    if (met) return StepStatus::done;
    if (elapsed > w->timeout_s) {
      failure_ = Text::format("condition not met within {:g} s", w->timeout_s);
      return StepStatus::failed;
    }
    return StepStatus::running;
  }
  const auto& r = std::get<recipe::Require>(ins.action);
  if (!r.homed_axes.empty() && !s.scu_status2_known) {
    // The SCU's "initialised" flags come with the first status read after activation.
    if (elapsed <= kStatusWaitS) return StepStatus::running;
    failure_ = Text::format("the SCU did not report whether the actuators are initialised within {:g} s",
                            kStatusWaitS);
    return StepStatus::failed;
  }
  for (int axis : r.homed_axes) {
    // The home record, checked against the devices as they are now.
    auto why = routines::check_homed(*record_, cell_, s, static_cast<std::size_t>(axis));
    if (why.size > 0) {
      failure_ = why;
      return StepStatus::failed;
    }
  }
  if (r.encoder_ready && !(s.encoder.data_exchange && s.encoder.ready)) {
    failure_ = Text::format("the encoder is not ready");
    return StepStatus::failed;
  }
  if (r.spindle_at_rest && !s.spindle.at_rest) {
    failure_ = Text::format("the spindle is not at rest ({:.0f} Hz)", s.spindle.actual_hz);
    return StepStatus::failed;
  }
  return StepStatus::done;
}

Supervisor::StepStatus Supervisor::run_teach_in(const cell::CellState& s, double t) {
  if (!teach_in_) {
    failure_ = Text::format("this cell has no encoder port to teach (the run was set up without one)");
    return StepStatus::failed;
  }
  teach_in_->step(s, std::nullopt, {}, t);
  intents_.axes = teach_in_->intents().axes;
  tell_teach_in(t);
  if (teach_in_->phase() == routines::TeachInPhase::done) return StepStatus::done;
  if (teach_in_->phase() != routines::TeachInPhase::failed) return StepStatus::running;
  failure_ = teach_in_->failure();
  return StepStatus::failed;
}

void Supervisor::wind_down_teach_in(const cell::CellState& s, std::optional<config::StopCategory> demanded,
                                    std::string_view stop_reason, double t) {
  if (teach_in_settled()) return;
  // The supervisor's halt stops the axis; the routine only waits for it, then restores the encoder.
  const auto category = demanded                    ? *demanded
                        : state_ == State::aborting ? config::StopCategory::immediate
                        : state_ == State::stopping ? config::StopCategory::controlled_off
                                                    : config::StopCategory::controlled_hold;
  // An operator's hold, stop or abort is named as the operator's; a monitor's stop by its rule.
  if (!demanded) teach_in_->abort(t);
  const auto why = demanded && !stop_reason.empty() ? Text::format("{}", stop_reason)
                                                    : Text::format("the run went to {}", to_string(state_));
  teach_in_->step(s, category, why.view(), t);
  tell_teach_in(t);
}

void Supervisor::tell_teach_in(double t) {
  if (teach_in_->phase() != told_phase_) {
    told_phase_ = teach_in_->phase();
    events_.post(t, journal::Note{Text::format("teach-in: {}", routines::to_string(told_phase_))});
  }
  if (teach_in_->prompt().view() != told_prompt_.view()) {
    told_prompt_ = teach_in_->prompt();
    if (!told_prompt_.view().empty())
      events_.post(t, journal::Note{Text::format("teach-in: {}", told_prompt_.view())});
  }
}

void Supervisor::sample(const cell::CellState& s, double t) {
  if (t < next_sample_t_) return;
  next_sample_t_ = t + settings_.sample_s;
  auto smp = cell_sample(s);
  for (std::size_t i = 0; i < s.axis_count; ++i) smp.planned_mm[i] = static_cast<float>(planned_mm(i));
  smp.spindle_set_hz = static_cast<float>(intents_.spindle.run ? intents_.spindle.frequency_hz : 0.0);
  events_.post(t, smp);
}

void Supervisor::step(const cell::CellState& s, std::optional<config::StopCategory> demanded, double t,
                      std::string_view stop_reason) {
  const State before = state_;
  intents_.spindle.reset = device_reset_requested_;
  device_reset_requested_ = false;
  if (pending_) {
    const Command c = *pending_;
    pending_.reset();
    const auto why = Text::format("{} by {}", to_string(c), pending_source_.view());
    switch (c) {
      case Command::start:
        pc_ = 0;
        instruction_started_ = false;
        failure_ = {};
        events_.post(t,
                     journal::RunStarted{recipe_.name, cell_.name, settings_.mode,
                                         static_cast<std::uint32_t>(step_count()), recipe::job_of(program_)});
        enter(State::starting, t, why);
        break;
      case Command::hold:
        enter(State::holding, t, why);
        break;
      case Command::unhold:
        if (demanded) {
          refusal_ = Text::format("unhold refused: a latched fault still demands a stop (reset it first)");
          events_.post(t, journal::Note{refusal_});
        } else {
          enter(State::unholding, t, why);
        }
        break;
      case Command::stop:
        enter(State::stopping, t, why);
        break;
      case Command::abort:
        enter(State::aborting, t, why);
        break;
      case Command::reset:
        enter(State::resetting, t, why);
        break;
      case Command::clear:
        enter(State::clearing, t, why);
        break;
    }
  }
  apply_demanded(demanded, t);

  intents_.halt = cell::Halt::none;
  switch (state_) {
    case State::idle:
    case State::complete:
    case State::stopped:
    case State::aborted:
      clear_motion();
      intents_.spindle.run = false;
      break;

    case State::starting: {
      bool up = s.scu_remote && s.encoder.data_exchange && s.encoder.ready;
      for (const auto& l : s.links) up = up && l.active;
      // A session that gave up while starting does not try again in this run: waiting for it out
      // to the start time-out would only hide its reason (the run reports it) behind a time.
      std::string_view failed;
      for (std::size_t d = 0; d < cell::kMaxDevices && failed.empty(); ++d)
        if (s.links[d].fault) failed = s.devices[d];
      if (up) {
        cell_up_ = true;
        enter(State::execute, t, Text::format("all devices up, encoder ready"));
      } else if (!failed.empty()) {
        failure_ = Text::format("{} session failed while starting (its reason follows)", failed);
        enter(State::aborting, t, failure_);
      } else if (t - state_since_ > settings_.start_timeout_s) {
        failure_ = Text::format("devices not ready after {:g} s ({})", settings_.start_timeout_s,
                                devices_up(s).view());
        enter(State::aborting, t, failure_);
      }
      break;
    }

    case State::execute: {
      if (pc_ >= program_.instructions.size()) {
        enter(State::completing, t, Text::format("all {} steps done", program_.instructions.size()));
        break;
      }
      if (!instruction_started_) start_instruction(s, t);
      const auto status = run_instruction(s, t);
      const auto& ins = program_.instructions[pc_];
      if (status == StepStatus::done) {
        events_.post(t, journal::StepEnded{static_cast<std::uint32_t>(pc_), ins.label, true, {}});
        clear_motion();
        ++pc_;
        instruction_started_ = false;
      } else if (status == StepStatus::failed) {
        events_.post(t, journal::StepEnded{static_cast<std::uint32_t>(pc_), ins.label, false, failure_});
        enter(State::stopping, t, Text::format("step {} failed: {}", pc_ + 1, failure_.view()));
      }
      break;
    }

    case State::holding:
      clear_motion();
      intents_.halt = cell::Halt::controlled;
      if (move_started()) executor_.hold(t);
      wind_down_teach_in(s, demanded, stop_reason, t);
      if (axes_still(s) && teach_in_settled()) enter(State::held, t, Text::format("axes at rest"));
      break;

    case State::held:
      clear_motion();
      if (move_started()) executor_.hold(t);
      wind_down_teach_in(s, demanded, stop_reason, t);
      break;

    case State::unholding:
      // A move goes on from the moving state the hold has reached (no stop first); any other step
      // starts again from where the cell is (a dwell keeps what it had done).
      if (move_started()) {
        executor_.resume(s, t, move_counter_);
      } else if (pc_ < program_.instructions.size() &&
                 !std::holds_alternative<recipe::Dwell>(program_.instructions[pc_].action)) {
        instruction_started_ = false;
      }
      last_execute_t_ = t;
      enter(State::execute, t, Text::format("resuming step {}", pc_ + 1));
      break;

    case State::completing:
      clear_motion();
      intents_.spindle.run = false;
      if (axes_still(s) && s.spindle.at_rest) {
        enter(State::complete, t, Text::format("cell at rest"));
        events_.post(t, journal::RunEnded{"complete"});
      }
      break;

    case State::stopping:
    case State::aborting: {
      const bool abort = state_ == State::aborting;
      clear_motion();
      intents_.spindle.run = false;
      intents_.halt = abort ? cell::Halt::immediate : cell::Halt::controlled;
      // A device whose session is down reports nothing more: waiting for it is pointless. An SCU that
      // no longer hears the keep-alive stops every actuator by its own watchdog.
      const bool scu_lost = !s.links[static_cast<std::size_t>(cell::Device::scu)].active;
      const bool spindle_lost = !s.links[static_cast<std::size_t>(cell::Device::spindle)].active;
      wind_down_teach_in(s, demanded, stop_reason, t);
      const bool rest =
          (axes_still(s) || scu_lost) && (s.spindle.at_rest || spindle_lost) && teach_in_settled();
      if (rest || t - state_since_ > settings_.stop_timeout_s) {
        const auto note =
            !rest ? Text::format("not at rest after {:g} s; giving up waiting", settings_.stop_timeout_s)
            : scu_lost || spindle_lost ? Text::format(
                                             "{} link lost: its rest is not known yet; the safe-stop "
                                             "that follows confirms or bounds it",
                                             scu_lost ? "SCU" : "spindle")
                                       : Text::format("cell at rest");
        enter(abort ? State::aborted : State::stopped, t, note);
        events_.post(t, journal::RunEnded{abort ? "aborted" : "stopped"});
      }
      break;
    }

    case State::clearing:
      // The abort acknowledged: everything is at rest already (Aborting ended only then).
      clear_motion();
      intents_.spindle.run = false;
      enter(State::stopped, t, Text::format("cleared: reset to reach Idle"));
      break;

    case State::resetting:
      clear_motion();
      intents_.spindle.reset = true;  // clears a converter fault whose cause is gone
      cell_up_ = false;
      enter(State::idle, t, Text::format("reset done"));
      break;
  }
  if (is_running_state(state_) || state_ == State::stopping || state_ == State::aborting) {
    sample(s, t);
  } else if (is_final(state_) && !is_final(before)) {
    // The cell as the run ended, whatever the sample period: else the record's last sample may show
    // a spindle still running down that stood still before the end.
    next_sample_t_ = t;
    sample(s, t);
  }
}

}  // namespace cellctl::supervisor

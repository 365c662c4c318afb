#include "routines/homing.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::routines {
namespace {

using config::HomingEnd;
using config::HomingStrategy;
using journal::Text;

constexpr double kBackOffMm = 3.0;          // away from an end the axis already stands at
constexpr double kEndWaitS = 5.0;           // for the SCU's end and "initialised" bits (status 2 every 2 s)
constexpr double kPresetWaitS = 3.0;        // for the encoder's preset handshake
constexpr double kPresetSettleS = 0.05;     // fresh inputs after the handshake before it is read back
constexpr double kPresetReadBackMm = 0.05;  // the preset read back within this
constexpr double kMoveToleranceMm = 0.1;    // homing moves end this close to their target

}  // namespace

const char* to_string(HomingPhase p) noexcept {
  switch (p) {
    case HomingPhase::idle:
      return "idle";
    case HomingPhase::waiting:
      return "waiting";
    case HomingPhase::back_off:
      return "backing off the end";
    case HomingPhase::to_end:
      return "to the end";
    case HomingPhase::at_end:
      return "at the end";
    case HomingPhase::preset:
      return "encoder preset";
    case HomingPhase::to_home:
      return "to the home position";
    case HomingPhase::homed:
      return "homed";
    case HomingPhase::failed:
      return "failed";
  }
  return "?";
}

Homing::Homing(const config::CellCore& cell, journal::EventSink& events, double dt, motion::MoveSettings move)
    : cell_(cell), events_(events), executor_(cell, limits_, dt, move) {
  limits_.axes.resize(cell.axes.size());
  double longest_s = 10.0;
  for (std::size_t i = 0; i < cell.axes.size(); ++i) {
    const auto& a = cell.axes[i];
    const double speed = a.homing.speed_mm_s > 0.0 ? a.homing.speed_mm_s : a.max_speed_mm_s;
    limits_.axes[i] = recipe::AxisLimits{.min_mm = a.min_mm,
                                         .max_mm = a.max_mm,
                                         .max_speed_mm_s = speed,
                                         .tolerance_mm = std::min(kMoveToleranceMm, a.homing.tolerance_mm)};
    longest_s = std::max(longest_s, 2.0 * (a.max_mm - a.min_mm) / speed);
  }
  limits_.move_timeout_s = longest_s;
  move_.targets.reserve(cell::kMaxAxes);
}

void Homing::enter(std::size_t i, HomingPhase p, const cell::CellState& s, double t) {
  phase_[i] = p;
  const auto& a = s.axes[i];
  if (a.measured)
    events_.post(t, journal::Note{Text::format("home {}: {} (SCU {:.2f} mm, encoder {:.3f} mm)",
                                               cell_.axes[i].name, to_string(p), a.scu_mm, a.encoder_mm)});
  else
    events_.post(t, journal::Note{Text::format("home {}: {} (SCU {:.2f} mm)", cell_.axes[i].name,
                                               to_string(p), a.scu_mm)});
}

HomingStatus Homing::fail(Text why) {
  reason_ = why;
  for (auto& p : phase_)
    if (p != HomingPhase::idle && p != HomingPhase::homed) p = HomingPhase::failed;
  return HomingStatus::failed;
}

void Homing::start(std::span<const int> axes, double t, HomeRecord& record) {
  record_ = &record;
  phase_.fill(HomingPhase::idle);
  in_group_.fill(false);
  reason_ = {};
  stage_ = Stage::next_group;
  stage_since_ = t;
  // A new homing of a cell whose record was made with another config starts the record afresh.
  previous_ = record.config_changed ? decltype(record.axes){} : record.axes;
  if (record.config_changed) {
    record.axes = {};
    record.config_changed = false;
  }
  for (int a : axes) {
    const auto i = static_cast<std::size_t>(a);
    phase_[i] = HomingPhase::waiting;
    record.axes[i] = {};  // whatever happens now, the old home no longer holds
  }
  record.updated = true;
}

bool Homing::refuse(const cell::CellState& s) {
  bool needs_encoder = false;
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    if (phase_[i] == HomingPhase::idle) continue;
    needs_encoder = needs_encoder || s.axes[i].measured;
    if (!s.axes[i].present) {
      reason_ = Text::format("not homing: the SCU does not report actuator {} (axis {})",
                             cell_.axes[i].actuator, cell_.axes[i].name);
      return true;
    }
    if (s.axes[i].actuator_fault) {
      reason_ = Text::format("not homing: actuator {} (axis {}) reports a fault", cell_.axes[i].actuator,
                             cell_.axes[i].name);
      return true;
    }
  }
  if (!s.spindle.at_rest || s.spindle.running) {
    reason_ = Text::format("not homing: the spindle turns ({:.0f} Hz): stop it first", s.spindle.actual_hz);
    return true;
  }
  const auto& scu = s.links[static_cast<std::size_t>(cell::Device::scu)];
  if (!scu.active || !s.scu_remote) {
    reason_ = Text::format("not homing: the SCU is not ready (remote mode not open)");
    return true;
  }
  if (s.scu_errors.any()) {
    reason_ = Text::format("not homing: the SCU reports error bit {} ({})", s.scu_errors.first_bit,
                           s.scu_errors.first_cause);
    return true;
  }
  if (needs_encoder && !(s.encoder.data_exchange && s.encoder.ready)) {
    reason_ = Text::format("not homing: the encoder is not ready (data exchange {})",
                           s.encoder.data_exchange ? "on, Ready bit clear" : "off");
    return true;
  }
  if (needs_encoder && (s.encoder.limit_switch || s.encoder.alarm)) {
    reason_ = Text::format("not homing: the encoder reports {}",
                           s.encoder.limit_switch ? "its limit switch active" : "an alarm");
    return true;
  }
  return false;
}

bool Homing::check_absolute(const cell::CellState& s, std::size_t i) {
  const auto& c = cell_.axes[i];
  const double enc = s.axes[i].encoder_mm;
  if (!(s.encoder.data_exchange && s.encoder.ready)) {
    reason_ = Text::format("axis {}: the encoder is not ready", c.name);
    return false;
  }
  if (enc < c.min_mm || enc > c.max_mm) {
    reason_ = Text::format("axis {}: the encoder reads {:.2f} mm, outside the travel [{:g}, {:g}] mm", c.name,
                           enc, c.min_mm, c.max_mm);
    return false;
  }
  // Homing again finds what the last homing found: the encoder still where the record has it.
  const auto& before = previous_[i];
  if (before.homed && before.strategy == HomingStrategy::absolute_encoder && before.measured) {
    const double expected = expected_encoder_mm(before, s.axes[i].scu_mm);
    if (std::abs(enc - expected) > c.homing.tolerance_mm) {
      reason_ = Text::format(
          "axis {}: encoder at {:.2f} mm, the home record expects {:.2f} mm: replaced? delete its entry in "
          "home.json to accept it",
          c.name, enc, expected);
      return false;
    }
  }
  return true;
}

double Homing::end_mm(std::size_t i) const noexcept {
  const auto& c = cell_.axes[i];
  return c.homing.end == HomingEnd::retracted ? c.min_mm : c.max_mm;
}

bool Homing::at_end(const cell::CellState& s, std::size_t i) const noexcept {
  const auto& a = s.axes[i];
  return cell_.axes[i].homing.end == HomingEnd::retracted ? a.at_retracted_end : a.at_extended_end;
}

bool Homing::start_move(HomingPhase phase, const cell::CellState& s, double t, std::uint32_t& move_id,
                        motion::Reference ref) {
  move_.targets.clear();
  move_.speed_mm_s = 0.0;
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    if (phase_[i] != phase) continue;
    const auto& c = cell_.axes[i];
    double target = c.homing.home_mm;
    if (phase == HomingPhase::to_end) target = end_mm(i);
    if (phase == HomingPhase::back_off)
      target = end_mm(i) + (c.homing.end == HomingEnd::retracted ? kBackOffMm : -kBackOffMm);
    move_.targets.push_back({static_cast<int>(i), target});
    const double v = c.homing.speed_mm_s;
    move_.speed_mm_s = move_.speed_mm_s == 0.0 ? v : std::min(move_.speed_mm_s, v);
  }
  if (move_.targets.empty()) return false;
  executor_.start(move_, s, t, move_id, ref);
  return true;
}

void Homing::begin_group(const cell::CellState& s, double t, std::uint32_t& move_id) {
  int sequence = 1 << 30;
  for (std::size_t i = 0; i < cell_.axes.size(); ++i)
    if (phase_[i] == HomingPhase::waiting) sequence = std::min(sequence, cell_.axes[i].homing.sequence);
  in_group_.fill(false);
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    if (phase_[i] != HomingPhase::waiting || cell_.axes[i].homing.sequence != sequence) continue;
    in_group_[i] = true;
    const auto& h = cell_.axes[i].homing;
    if (h.strategy == HomingStrategy::absolute_encoder) continue;  // judged in finish_group
    const bool needs_end = h.strategy == HomingStrategy::end_position || !s.axes[i].scu_initialised;
    if (!needs_end) {
      enter(i, HomingPhase::to_home, s, t);
      continue;
    }
    const bool standing_at_end = at_end(s, i) || std::abs(s.axes[i].scu_mm - end_mm(i)) < kBackOffMm;
    enter(i, standing_at_end ? HomingPhase::back_off : HomingPhase::to_end, s, t);
  }
  stage_since_ = t;
  if (start_move(HomingPhase::back_off, s, t, move_id, motion::Reference::scu)) {
    stage_ = Stage::back_off;
  } else if (start_move(HomingPhase::to_end, s, t, move_id, motion::Reference::scu)) {
    stage_ = Stage::to_end;
  } else if (start_move(HomingPhase::to_home, s, t, move_id, motion::Reference::best)) {
    stage_ = Stage::to_home;
  } else {
    stage_ = Stage::to_home;  // nothing moves: the group is judged and recorded at once
  }
}

void Homing::finish_group(const cell::CellState& s, double t) {
  for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
    if (!in_group_[i]) continue;
    auto& h = record_->axes[i];
    h.homed = true;
    h.strategy = cell_.axes[i].homing.strategy;
    h.measured = s.axes[i].measured;
    h.encoder_mm = s.axes[i].encoder_mm;
    h.scu_mm = s.axes[i].scu_mm;
    h.run_t = t;
    enter(i, HomingPhase::homed, s, t);
  }
  record_->updated = true;
  in_group_.fill(false);
  stage_ = Stage::next_group;
}

HomingStatus Homing::step(const cell::CellState& s, double t, cell::Intents& out, std::uint32_t& move_id,
                          std::uint32_t& preset_id) {
  const double in_stage = t - stage_since_;
  switch (stage_) {
    case Stage::next_group: {
      bool any_waiting = false;
      bool first = true;
      for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
        any_waiting = any_waiting || phase_[i] == HomingPhase::waiting;
        first = first && (phase_[i] == HomingPhase::waiting || phase_[i] == HomingPhase::idle);
      }
      if (!any_waiting) return HomingStatus::done;
      if (first && refuse(s)) return fail(reason_);
      begin_group(s, t, move_id);
      return HomingStatus::running;
    }
    case Stage::back_off:
    case Stage::to_end:
    case Stage::to_home: {
      const auto status = executor_.step(s, t, out, move_id);
      // (A correction in motion on the way home, say.)
      if (!executor_.note().empty()) journal::post_note(events_, t, "homing: {}", executor_.note());
      if (status == motion::MoveStatus::failed) return fail(executor_.reason());
      if (status == motion::MoveStatus::running) return HomingStatus::running;
      stage_since_ = t;
      if (stage_ == Stage::back_off) {
        for (std::size_t i = 0; i < cell_.axes.size(); ++i)
          if (phase_[i] == HomingPhase::back_off) enter(i, HomingPhase::to_end, s, t);
        // (Never without an axis: those that backed off go on into their end.)
        (void)start_move(HomingPhase::to_end, s, t, move_id, motion::Reference::scu);
        stage_ = Stage::to_end;
      } else if (stage_ == Stage::to_end) {
        for (std::size_t i = 0; i < cell_.axes.size(); ++i)
          if (phase_[i] == HomingPhase::to_end) enter(i, HomingPhase::at_end, s, t);
        stage_ = Stage::at_end;
      } else {
        for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
          if (!in_group_[i] || cell_.axes[i].homing.strategy != HomingStrategy::absolute_encoder) continue;
          if (!check_absolute(s, i)) return fail(reason_);
        }
        finish_group(s, t);
      }
      return HomingStatus::running;
    }
    case Stage::at_end: {
      bool all = true;
      for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
        if (phase_[i] != HomingPhase::at_end) continue;
        const auto& a = s.axes[i];
        const bool initialised =
            cell_.axes[i].homing.strategy != HomingStrategy::scu_initialised || a.scu_initialised;
        if (!a.moving && !a.commanded && at_end(s, i) && initialised) continue;
        all = false;
        if (in_stage > kEndWaitS)
          return fail(Text::format(
              "axis {}: the SCU did not report actuator {} {} at its {} end within {:g} s "
              "(SCU at {:.2f} mm)",
              cell_.axes[i].name, cell_.axes[i].actuator, initialised ? "at rest" : "initialised",
              cell_.axes[i].homing.end == HomingEnd::retracted ? "retracted" : "extended", kEndWaitS,
              a.scu_mm));
      }
      if (!all) return HomingStatus::running;
      stage_since_ = t;
      for (std::size_t i = 0; i < cell_.axes.size(); ++i) {
        if (phase_[i] != HomingPhase::at_end) continue;
        if (cell_.axes[i].homing.strategy == HomingStrategy::end_position && s.axes[i].measured) {
          enter(i, HomingPhase::preset, s, t);
          preset_axis_ = i;
          preset_id_ = ++preset_id;
          out.encoder = {.preset_id = preset_id_, .preset_mm = cell_.axes[i].homing.preset_mm};
          stage_ = Stage::preset;
          return HomingStatus::running;
        }
      }
      for (std::size_t i = 0; i < cell_.axes.size(); ++i)
        if (phase_[i] == HomingPhase::at_end) enter(i, HomingPhase::to_home, s, t);
      if (!start_move(HomingPhase::to_home, s, t, move_id, motion::Reference::best))
        finish_group(s, t);
      else
        stage_ = Stage::to_home;
      return HomingStatus::running;
    }
    case Stage::preset: {
      const auto& e = s.encoder;
      if (e.preset_id == preset_id_ && e.preset_failed)
        return fail(Text::format("axis {}: encoder preset failed: {}", cell_.axes[preset_axis_].name,
                                 e.preset_failure));
      if (e.preset_id == preset_id_ && e.preset_done) {
        stage_ = Stage::preset_read;
        stage_since_ = t;
        return HomingStatus::running;
      }
      if (in_stage > kPresetWaitS)
        return fail(Text::format("axis {}: the encoder did not acknowledge the preset within {:g} s",
                                 cell_.axes[preset_axis_].name, kPresetWaitS));
      return HomingStatus::running;
    }
    case Stage::preset_read: {
      if (in_stage < kPresetSettleS) return HomingStatus::running;
      const auto i = preset_axis_;
      const double want = cell_.axes[i].homing.preset_mm;
      if (!s.encoder.ready || std::abs(s.axes[i].encoder_mm - want) > kPresetReadBackMm)
        return fail(Text::format("axis {}: the encoder reads {:.3f} mm after the preset to {:.3f} mm",
                                 cell_.axes[i].name, s.axes[i].encoder_mm, want));
      events_.post(t, journal::Note{Text::format("home {}: encoder preset to {:.3f} mm, reads {:.3f} mm",
                                                 cell_.axes[i].name, want, s.axes[i].encoder_mm)});
      for (std::size_t k = 0; k < cell_.axes.size(); ++k)
        if (phase_[k] == HomingPhase::at_end || phase_[k] == HomingPhase::preset)
          enter(k, HomingPhase::to_home, s, t);
      stage_since_ = t;
      if (!start_move(HomingPhase::to_home, s, t, move_id, motion::Reference::best))
        finish_group(s, t);
      else
        stage_ = Stage::to_home;
      return HomingStatus::running;
    }
  }
  return HomingStatus::running;
}

}  // namespace cellctl::routines

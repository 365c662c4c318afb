#include "motion/move_executor.hpp"

#include <algorithm>
#include <cmath>

#include "motion/move_limits.hpp"

namespace cellctl::motion {

MoveExecutor::MoveExecutor(const config::CellCore& cell, const recipe::Limits& limits, double dt,
                           MoveSettings settings)
    : cell_(cell), limits_(limits), settings_(settings), planner_(dt) {}

namespace {

// The time of a trapezoid (or triangle) over `distance` at cruise speed v and ramp `accel`.
double trapezoid_s(double distance, double v, double accel) noexcept {
  if (distance <= 0.0) return 0.0;
  return distance >= v * v / accel ? distance / v + v / accel : 2.0 * std::sqrt(distance / accel);
}

// The cruise speed whose trapezoid over `distance` at ramp `accel` takes `duration`: the smaller
// root of v^2 / accel - duration v + distance = 0 (the whole duration when even the triangle is
// longer: the fastest the ramp allows).
double speed_for_s(double distance, double duration, double accel) noexcept {
  if (distance <= 0.0 || duration <= 0.0) return 0.0;
  const double disc = duration * duration - 4.0 * distance / accel;
  if (disc <= 0.0) return accel * duration / 2.0;
  return 2.0 * distance / (duration + std::sqrt(disc));
}

// A trapezoid entered already moving at v0 towards the target (v0 <= its cruise speed) is the tail
// of one from rest that began v0 / accel earlier, v0^2 / 2 accel further back.
struct RestEquivalent {
  double extra_mm = 0.0;
  double earlier_s = 0.0;
};
RestEquivalent rest_equivalent(double v0, double accel) noexcept {
  return {v0 * v0 / (2.0 * accel), v0 / accel};
}

}  // namespace

double MoveExecutor::best_position(const cell::CellState& s, std::size_t i) const noexcept {
  return reference_ == Reference::scu ? s.axes[i].scu_mm : s.axes[i].position_mm();
}

void MoveExecutor::start(const recipe::Move& move, const cell::CellState& s, double t, std::uint32_t& move_id,
                         Reference reference) {
  axes_ = {};
  reference_ = reference;
  speed_ = move.speed_mm_s;
  synchronization_ =
      move.path == recipe::Path::line ? planner::Synchronization::phase : planner::Synchronization::time;
  reason_ = {};
  corrections_total_ = 0;
  held_since_.reset();
  for (const auto& target : move.targets) {
    const auto i = static_cast<std::size_t>(target.axis);
    auto& a = axes_[i];
    a.in_move = true;
    a.target_mm = target.target_mm;
    // Carry the SCU's present offset from the measurement into its target: fewer corrections later.
    a.scu_target_mm = s.axes[i].scu_mm + (a.target_mm - best_position(s, i));
    a.tolerance_mm = limits_.axes[i] ? limits_.axes[i]->tolerance_mm : 0.05;
  }
  plan(s, t, move_id, Motions{});
  // The move's planned time: the slowest axis's trapezoid from rest (as the SCU runs it).
  planned_s_ = 0.0;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    const auto& a = axes_[i];
    if (!a.in_move) continue;
    const double v = std::min(speed_, cell_.axes[i].max_speed_mm_s);
    planned_s_ = std::max(planned_s_,
                          trapezoid_s(std::abs(a.target_mm - a.start_mm), v, cell_.axes[i].max_accel_mm_s2));
  }
}

void MoveExecutor::hold(double t) noexcept {
  if (!held_since_) {
    held_since_ = t;
    for (std::size_t i = 0; i < cell::kMaxAxes; ++i) held_from_[i] = {planned_[i], planned_speed_[i], 0.0};
  }
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    if (!axes_[i].in_move) continue;
    const auto braking = braked(i, t - *held_since_);
    planned_[i] = braking.position;
    planned_speed_[i] = braking.velocity;
  }
}

planner::MotionState MoveExecutor::braked(std::size_t i, double since) const noexcept {
  // The SCU's soft stop (RS) takes the speed down at the actuator's ramp (max_accel_mm_s2 is read as
  // that ramp, as for the trapezoids): no jerk limit of its own.
  const auto& from = held_from_[i];
  const double ramp = cell_.axes[i].max_accel_mm_s2;
  const double stop_s = std::abs(from.velocity) / ramp;
  const double tau = std::clamp(since, 0.0, stop_s);
  const double decel = -std::copysign(ramp, from.velocity);
  return {from.position + from.velocity * tau + 0.5 * decel * tau * tau, from.velocity + decel * tau,
          since < stop_s ? decel : 0.0};
}

void MoveExecutor::resume(const cell::CellState& s, double t, std::uint32_t& move_id) {
  Motions from{};
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    if (!axes_[i].in_move || !held_since_) continue;
    const auto braking = braked(i, t - *held_since_);
    from[i] = {braking.velocity, braking.acceleration};
  }
  held_since_.reset();
  reason_ = {};
  plan(s, t, move_id, from);
}

void MoveExecutor::plan(const cell::CellState& s, double t, std::uint32_t& move_id, const Motions& from) {
  // The SCU runs each actuator as a trapezoid at its own ramp (max_accel_mm_s2 is read as the SCU's
  // soft ramp), one already moving towards its target from its present speed: the move takes as long
  // as the slowest axis's trapezoid at the move speed.
  double duration = 0.0;
  double lead = 0.0;
  std::array<RestEquivalent, cell::kMaxAxes> entered{};
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    if (!a.in_move) continue;
    a.start_mm = best_position(s, i);
    a.start_scu_mm = s.axes[i].scu_mm;
    a.anchored = from[i].velocity == 0.0 && from[i].acceleration == 0.0 && !s.axes[i].moving;
    a.correcting_at_rest = false;
    a.sampled_mm_s = 0.0;
    a.drift.reset();
    const double to_go = a.target_mm - a.start_mm;
    const double v = std::min(speed_, cell_.axes[i].max_speed_mm_s);
    const double ramp = cell_.axes[i].max_accel_mm_s2;
    const double towards = std::clamp(std::copysign(from[i].velocity, from[i].velocity * to_go), 0.0, v);
    entered[i] = rest_equivalent(towards, ramp);
    duration = std::max(duration,
                        trapezoid_s(std::abs(to_go) + entered[i].extra_mm, v, ramp) - entered[i].earlier_s);
    lead = std::max(lead, std::abs(to_go));
  }
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    planned_[i] = i < s.axis_count ? best_position(s, i) : 0.0;
    planned_speed_[i] = from[i].velocity;
    if (!a.in_move) continue;
    const auto& c = cell_.axes[i];
    // Coordinated: each axis gets the speed whose trapezoid takes that long, so that all arrive
    // together (speeds in proportion to the distances would not: the ramps differ); never below the
    // speed at which the actuator moves at all.
    const double v = speed_for_s(std::abs(a.target_mm - a.start_mm) + entered[i].extra_mm,
                                 duration + entered[i].earlier_s, c.max_accel_mm_s2);
    a.nominal_speed = std::clamp(v, std::min(c.min_speed_mm_s * 1.2, speed_), c.max_speed_mm_s);
    speed_sent_[i] = a.nominal_speed;
  }

  input_ = {};
  input_.synchronization = synchronization_;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    const auto& a = axes_[i];
    const auto k = static_cast<Eigen::Index>(i);
    input_.enabled[i] = a.in_move;
    input_.current_position[k] = planned_[i];
    input_.current_velocity[k] = from[i].velocity;
    input_.current_acceleration[k] = from[i].acceleration;
    input_.target_position[k] = a.in_move ? a.target_mm : input_.current_position[k];
    if (i < cell_.axes.size()) limit_axis(cell_, speed_, i, input_);
  }

  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    a.commanded = false;
    clock_from_[i] = t;
    // An axis inside its tolerance is left alone, unless it still moves (braking from a hold).
    if (!a.in_move || (std::abs(a.target_mm - a.start_mm) <= a.tolerance_mm && from[i].velocity == 0.0))
      continue;
    a.commanded = true;
    a.move_id = ++move_id;
    a.commanded_at = t;
    a.taken_before = s.axes[i].moves_taken;
    if (from[i].velocity == 0.0 && from[i].acceleration == 0.0) clock_from_[i].reset();  // until taken
  }
  calculated_ = false;
  started_t_ = t;
  last_progress_t_ = t;
  last_speed_update_t_ = t;
  best_remaining_ = lead;
  still_since_.reset();
  seen_moving_ = {};
  last_scu_age_ = s.scu_position_age;
}

double MoveExecutor::reachable_scu_target(std::size_t i, double mm) const noexcept {
  const auto& c = cell_.axes[i];
  return std::clamp(mm, std::max(0.0, c.min_mm - cell_.limits.disagreement_mm),
                    c.max_mm + cell_.limits.disagreement_mm);
}

void MoveExecutor::follow_plan(const cell::CellState& s, double t) {
  if (!calculated_) {
    // An invalid profile (it cannot be: limits are validated at load) leaves the plan where it began.
    if (planner::is_error(planner_.update(input_, output_))) return;
    calculated_ = true;
    if (!output_.note.empty()) note_ = journal::Text::format("{}", output_.note);
  }
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    const auto& a = axes_[i];
    if (!a.in_move) continue;
    if (!clock_from_[i] && s.axes[i].moves_taken != a.taken_before) clock_from_[i] = t;
    if (!clock_from_[i]) continue;  // its plan stands where it began until the SCU takes the move
    // One cycle on at its first: as the planner steps (the state a cycle after the start).
    const auto at =
        planner_.trajectory().profile(static_cast<int>(i)).at(t - *clock_from_[i] + planner_.dt());
    planned_[i] = at.position;
    planned_speed_[i] = at.velocity;
  }
}

void MoveExecutor::correct_in_motion(const cell::CellState& s, double t, std::uint32_t& move_id) {
  // A sample needs a fresh SCU reading (a keep-alive reply): between replies it stands still.
  const bool fresh = s.scu_position_age < last_scu_age_;
  last_scu_age_ = s.scu_position_age;
  if (!fresh || reference_ != Reference::best) return;
  const double age_s = link::to_seconds(s.scu_position_age);
  // Fresh, the reading is as old as its RC's round trip. A correction in motion costs the axis an RS,
  // two RTs and an RE on the line (an RC between each when due) while it runs down from the RS: on a
  // slow line it would stall the axis behind its plan for longer than it saves. Left to the correction
  // at rest there.
  if (age_s > settings_.max_round_trip_to_correct_s) return;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    const auto& st = s.axes[i];
    if (!a.in_move || !a.commanded || !a.anchored || a.in_motion_move_id != 0 ||
        !cell_.axes[i].correct_in_motion || !st.measured || !st.moving ||
        a.corrections >= settings_.max_corrections)
      continue;
    // Only samples at a steady speed towards the target (no ramp: the SCU's reply delay then
    // shifts each offset by its speed's share, which OffsetSlope takes out).
    const double v = st.encoder_mm_s;
    const double to_go = a.target_mm - st.encoder_mm;
    const bool steady = v * to_go > 0.0 && std::abs(v - a.sampled_mm_s) <= 0.05 * std::abs(v);
    a.sampled_mm_s = v;
    if (!steady) continue;
    const double at = st.encoder_mm - v * age_s;  // where the encoder was when the reply came
    a.drift.add(at, v, st.scu_mm - at);
    // Judged once the samples span a quarter of the travel, the drift is three times its standard
    // error (a real one, not the scatter of the SCU's 0.1 mm edges) and no larger than a sensor's
    // plausible scale error (beyond that something slips: left to the correction at rest and the
    // monitor), and the correction it gives is known to a quarter of the tolerance and worth one;
    // given only while the SCU is still short of its own approach (its braking distance, and half a
    // second for the RS, RT and RE on the line).
    const double travel = a.target_mm - a.start_mm;
    const double slope = a.drift.slope();
    const double error = a.drift.slope_error();
    const double change = slope * travel;
    const double ramp = cell_.axes[i].max_accel_mm_s2;
    if (a.drift.count() < 8 || a.drift.span_mm() < 0.25 * std::abs(travel) || std::abs(slope) < 3.0 * error ||
        std::abs(slope) > settings_.max_scale_error || error * std::abs(travel) > a.tolerance_mm / 4.0 ||
        std::abs(change) < a.tolerance_mm / 4.0 || std::abs(to_go) < v * v / (2.0 * ramp) + std::abs(v) * 0.5)
      continue;
    // The SCU's offset at the start, where both stood still, plus the drift over the travel.
    retarget(i, a.start_scu_mm + travel + change, t, move_id);
    a.in_motion_move_id = a.move_id;
    note_ = journal::Text::format(
        "axis {} corrected while moving: its SCU reads {:+.2f} % along the travel, so its SCU target "
        "moves by {:+.3f} mm",
        cell_.axes[i].name, 100.0 * slope, change);
  }
}

void MoveExecutor::retarget(std::size_t i, double scu_target_mm, double t, std::uint32_t& move_id) {
  auto& a = axes_[i];
  a.scu_target_mm = reachable_scu_target(i, scu_target_mm);
  a.move_id = ++move_id;
  a.commanded_at = t;
  a.commanded = true;
  ++a.corrections;
  ++corrections_total_;
}

void MoveExecutor::command(cell::Intents& out) const noexcept {
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    if (!axes_[i].commanded) continue;
    auto& intent = out.axes[i];
    intent.move_id = axes_[i].move_id;
    intent.move = true;
    intent.target_mm = axes_[i].scu_target_mm;
    intent.speed_mm_s = speed_sent_[i];
    intent.soft = true;
    intent.planned_mm = planned_[i];
    intent.planned_mm_s = planned_speed_[i];
  }
}

MoveStatus MoveExecutor::step(const cell::CellState& s, double t, cell::Intents& out,
                              std::uint32_t& move_id) {
  // The profile: where the axes should be, and the pace the modulation keeps them on.
  // An invalid profile (it cannot be: limits are validated at load) would leave the plan where it is.
  note_ = {};
  follow_plan(s, t);
  double worst_remaining = 0.0;
  bool all_inside = true;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    const auto& a = axes_[i];
    if (!a.in_move) continue;
    const double remaining = std::abs(a.target_mm - best_position(s, i));
    worst_remaining = std::max(worst_remaining, remaining);
    if (remaining > a.tolerance_mm) all_inside = false;
    if (s.axes[i].moving) seen_moving_[i] = true;
  }
  correct_in_motion(s, t, move_id);

  if (worst_remaining < best_remaining_ - 0.05) {
    best_remaining_ = worst_remaining;
    last_progress_t_ = t;
  }
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    // (Not in the cycle that sent the command: that cycle's state is from before it.)
    if (!a.commanded || !s.axes[i].move_refused || t <= a.commanded_at) continue;
    if (a.move_id == a.in_motion_move_id) {
      // The SCU would not take a new RE while the axis still ran down from the RS before it (the
      // manual does not say it must): the RS has stopped the axis mid-move.
      reason_ = journal::Text::format(
          "the SCU refused axis {}'s corrected target while it moved ({}); set its correct_in_motion: false",
          cell_.axes[i].name, s.scu_refusal.empty() ? "no reason given" : s.scu_refusal);
      return MoveStatus::failed;
    }
    reason_ = journal::Text::format("the SCU refused the move of axis {} to {:.3f} mm ({})",
                                    cell_.axes[i].name, axes_[i].scu_target_mm,
                                    s.scu_refusal.empty() ? "no reason given" : s.scu_refusal);
    return MoveStatus::failed;
  }
  if (t - started_t_ > limits_.move_timeout_s) {
    reason_ = journal::Text::format("move not done after {:.1f} s (time-out); {:.2f} mm still to go",
                                    t - started_t_, worst_remaining);
    return MoveStatus::failed;
  }

  const bool any_moving = [&] {
    for (std::size_t i = 0; i < cell::kMaxAxes; ++i)
      if (axes_[i].in_move && s.axes[i].moving) return true;
    return false;
  }();

  if (!all_inside && t - last_progress_t_ > settings_.no_motion_s) {
    for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
      const auto& a = axes_[i];
      if (!a.in_move || std::abs(a.target_mm - best_position(s, i)) <= a.tolerance_mm) continue;
      reason_ = journal::Text::format(
          "no motion: axis {} stayed at {:.2f} mm for {:.1f} s at {:.2f} mm/s (below the actuator's "
          "threshold, or "
          "blocked?)",
          cell_.axes[i].name, best_position(s, i), t - last_progress_t_, speed_sent_[i]);
      break;
    }
    return MoveStatus::failed;
  }

  // Keep each axis on its planned profile (and so coordinated axes on their common one, a line or
  // not): an axis behind its plan gets a little more speed, by its lag as a share of its move.
  if (any_moving && t - last_speed_update_t_ >= settings_.speed_update_s) {
    last_speed_update_t_ = t;
    for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
      auto& a = axes_[i];
      const double span = a.target_mm - a.start_mm;
      // (Not during a correction at rest: that is a short move of its own.)
      if (!a.in_move || std::abs(span) < 1e-9 || a.correcting_at_rest) continue;
      const double lag = (planned_[i] - best_position(s, i)) / span;
      const double factor = std::clamp(1.0 + settings_.sync_gain * lag, 0.5, 1.5);
      const double axis_max =
          limits_.axes[i] ? limits_.axes[i]->max_speed_mm_s : cell_.axes[i].max_speed_mm_s;
      const double v = std::clamp(a.nominal_speed * factor,
                                  std::min(cell_.axes[i].min_speed_mm_s * 1.2, axis_max), axis_max);
      if (std::abs(v - speed_sent_[i]) > 0.03 * a.nominal_speed) speed_sent_[i] = v;
    }
  }

  // Judge only once the SCU has stopped and stayed stopped for a moment.
  bool judged_still = !any_moving;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    const auto& a = axes_[i];
    const bool needs_motion = a.in_move && std::abs(a.target_mm - best_position(s, i)) > a.tolerance_mm;
    if (needs_motion && !seen_moving_[i]) judged_still = false;  // not started yet
  }
  if (all_inside && !any_moving) {
    command(out);
    return MoveStatus::done;
  }
  if (!judged_still) {
    still_since_.reset();
    command(out);
    return MoveStatus::running;
  }
  if (!still_since_) still_since_ = t;
  if (t - *still_since_ < settings_.settle_s) {
    command(out);
    return MoveStatus::running;
  }

  // Stopped, yet outside the tolerance: the SCU's idea of the position is off. Correct and go again.
  bool corrected = false;
  for (std::size_t i = 0; i < cell::kMaxAxes; ++i) {
    auto& a = axes_[i];
    if (!a.in_move) continue;
    const double error = a.target_mm - best_position(s, i);
    if (std::abs(error) <= a.tolerance_mm) continue;
    if (a.corrections >= settings_.max_corrections) {
      reason_ = journal::Text::format("axis {} at {:.3f} mm after {} corrections, target {:.3f} ± {:g} mm",
                                      cell_.axes[i].name, best_position(s, i), a.corrections, a.target_mm,
                                      a.tolerance_mm);
      return MoveStatus::failed;
    }
    // From the SCU's target, which it reached: more exact than its reading, in 0.1 mm edges.
    retarget(i, a.scu_target_mm + error, t, move_id);
    a.correcting_at_rest = true;
    seen_moving_[i] = false;
    // A short correction at full share of the speed is fine; never below the threshold.
    speed_sent_[i] = std::max(a.nominal_speed, cell_.axes[i].min_speed_mm_s * 1.2);
    corrected = true;
  }
  if (corrected) {
    still_since_.reset();
    last_progress_t_ = t;
    best_remaining_ = worst_remaining;
  }
  command(out);
  return MoveStatus::running;
}

}  // namespace cellctl::motion

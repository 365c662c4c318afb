#pragma once
// A planned multi-axis motion: per axis a jerk profile (brake included), all starting now.
// calculate() builds it from an Input with the synchronisation asked for:
// - time: the smallest duration feasible for every axis (at least each axis's shortest, outside
//   every axis's blocked intervals); each axis then re-profiled to end exactly then;
// - phase: one scalar profile s: 0 -> 1 along the straight line from the current to the target
//   positions, with the tightest scaled limits of all axes — possible only when the current and
//   target velocities and accelerations are all on that line and the target keeps the line's
//   limits; otherwise time synchronisation and a note;
// - none: every axis on its own shortest profile.
// Every axis's motion (overshoot included) must stay in its travel, or the plan is refused. An
// axis whose time-synchronised blend leaves it gets a profile of the common duration that keeps it
// if its own shortest motion does and its target is at rest (travel_fit.hpp); a refusal names the
// end of the travel and by how much the motion the planner could make leaves it.
// Fixed-size storage: calculating and evaluating never allocate.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>

#include "planner/axis_profile.hpp"
#include "planner/input.hpp"
#include "planner/jerk_profile.hpp"
#include "planner/rest_to_rest.hpp"
#include "planner/result.hpp"
#include "planner/travel_fit.hpp"

namespace cellctl::planner {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline constexpr std::string_view kPhaseFallbackNote =
    "phase synchronisation impossible (the current or target velocities and accelerations are not on the "
    "line between the positions): time-synchronised instead";
inline constexpr std::string_view kPhaseLimitsNote =
    "phase synchronisation impossible (the target's velocity and acceleration break the limits along the "
    "line, which take each bound from the axis it binds most): time-synchronised instead";
inline constexpr std::string_view kPhaseBrakeNote =
    "phase synchronisation impossible (the start is beyond the limits along the line, which take each bound "
    "from the axis it binds most, so a brake along it could take an axis past its own): time-synchronised, "
    "each axis braking within its own limits";
inline constexpr std::string_view kPhaseTravelNote =
    "phase synchronisation impossible (the straight-line motion leaves an axis's travel): "
    "time-synchronised instead";

template <int N>
class Trajectory {
  static constexpr auto kN = static_cast<std::size_t>(N);

 public:
  Trajectory() = default;
  // Copies only the blocked intervals in use (the other slots are unset): zeroing and copying all
  // of them cost a rep stos and, for 6 axes, a rep movs per plan, whose start-ups cost more than the
  // intervals.
  Trajectory(const Trajectory& other) noexcept { *this = other; }
  Trajectory& operator=(const Trajectory& other) noexcept {
    profiles_ = other.profiles_;
    min_duration_ = other.min_duration_;
    input_ = other.input_;
    blocked_count_ = other.blocked_count_;
    for (std::size_t i = 0; i < kN; ++i) {
      for (std::size_t b = 0; b < blocked_count_[i]; ++b) blocked_[i][b] = other.blocked_[i][b];
    }
    enabled_ = other.enabled_;
    duration_ = other.duration_;
    synchronization_ = other.synchronization_;
    note_ = other.note_;
    return *this;
  }
  ~Trajectory() = default;

  [[nodiscard]] double duration() const noexcept { return duration_; }
  [[nodiscard]] bool enabled(int axis) const noexcept { return enabled_[idx(axis)]; }
  [[nodiscard]] Synchronization synchronization() const noexcept { return synchronization_; }
  [[nodiscard]] std::string_view note() const noexcept { return note_; }
  [[nodiscard]] const JerkProfile& profile(int axis) const noexcept { return profiles_[idx(axis)]; }

  // The state of every enabled axis at time t since the start (before 0 the start, after an axis's
  // end its target). Disabled axes are left as they are in the vectors.
  void at_time(double t, Vector<N>& p, Vector<N>& v, Vector<N>& a, Vector<N>& j) const noexcept {
    for (int i = 0; i < N; ++i) {
      if (!enabled_[idx(i)]) continue;
      const MotionState s = profiles_[idx(i)].at(t);
      p[i] = s.position;
      v[i] = s.velocity;
      a[i] = s.acceleration;
      j[i] = profiles_[idx(i)].jerk_at(t);
    }
  }
  [[nodiscard]] PositionExtrema position_extrema(int axis) const noexcept {
    return profiles_[idx(axis)].extrema();
  }
  // Each axis on its own: its shortest duration and the durations it cannot do (brake included).
  // An axis's shortest duration that did not set the common one is searched on each call (calculate()
  // leaves it, see AxisProfile::reaches_by; nothing is written, so concurrent readers are safe).
  [[nodiscard]] double axis_min_duration(int axis) const noexcept {
    const double known = min_duration_[idx(axis)];
    if (!std::isnan(known)) return known;
    AxisProfile a;
    const AxisStatus s = a.plan(start_of(input_, axis), target_of(input_, axis), limits_of(input_, axis));
    return s == AxisStatus::ok ? a.min_duration() : known;
  }
  [[nodiscard]] std::size_t blocked_count(int axis) const noexcept { return blocked_count_[idx(axis)]; }
  [[nodiscard]] const Interval& blocked(int axis, std::size_t i) const noexcept {
    return blocked_[idx(axis)][i];
  }

  // Plans `in`; on an error the trajectory is unchanged and `error_axis` names the axis; with
  // outside_travel, `excess` (if given) says which end of its travel and by how much; with
  // target_outside_limits, `refusal` (if given) which limit and by how much.
  [[nodiscard]] static Result calculate(const Input<N>& in, Trajectory& out, int& error_axis,
                                        TravelExcess* excess = nullptr,
                                        TargetExcess* refusal = nullptr) noexcept;

 private:
  static constexpr std::size_t idx(int axis) noexcept { return static_cast<std::size_t>(axis); }

  static AxisLimits limits_of(const Input<N>& in, int i) noexcept {
    const double vmin = in.min_velocity[i] == in.min_velocity[i] ? in.min_velocity[i] : -in.max_velocity[i];
    const double amin =
        in.min_acceleration[i] == in.min_acceleration[i] ? in.min_acceleration[i] : -in.max_acceleration[i];
    return AxisLimits{in.max_velocity[i], vmin, in.max_acceleration[i], amin, in.max_jerk[i]};
  }
  // An axis's start and target states, as given.
  static MotionState start_of(const Input<N>& in, int i) noexcept {
    return MotionState{in.current_position[i], in.current_velocity[i], in.current_acceleration[i]};
  }
  static MotionState target_of(const Input<N>& in, int i) noexcept {
    return MotionState{in.target_position[i], in.target_velocity[i], in.target_acceleration[i]};
  }
  // Checks every enabled axis's states and limits, and sets its limits in `limits` (the others unset).
  static Result validate(const Input<N>& in, int& axis, std::array<AxisLimits, kN>& limits) noexcept;
  static Result status_result(AxisStatus s) noexcept {
    switch (s) {
      case AxisStatus::target_outside_limits:
        return Result::target_outside_limits;
      default:
        return Result::unsupported_target;
    }
  }
  [[nodiscard]] bool plan_phase(const Input<N>& in, const std::array<AxisLimits, kN>& limits, int& error_axis,
                                Result& r) noexcept;
  [[nodiscard]] static bool plan_rest_to_rest(const Input<N>& in, const std::array<AxisLimits, kN>& limits,
                                              Trajectory& out) noexcept;
  // Whether an enabled axis has a travel to keep (an end that is finite).
  static bool bounded(const Input<N>& in) noexcept {
    for (int i = 0; i < N; ++i) {
      if (in.enabled[idx(i)] && !(in.min_position[i] == -kInf && in.max_position[i] == kInf)) return true;
    }
    return false;
  }
  // The longest of the enabled axes' shortest durations (+infinity when a search failed). Without
  // synchronisation every axis's is searched; otherwise only those of the axes that could set it.
  [[nodiscard]] static double longest_min_duration(const Input<N>& in,
                                                   const std::array<AxisProfile, kN>& axes) noexcept;
  // Time synchronisation: `common` moved out of every axis's blocked intervals. Then each enabled
  // axis prepared (AxisProfile::prepare) at `common`, or at its own shortest duration without
  // synchronisation; false, with `error_axis`, when one misses its target (only with a non-zero
  // target acceleration, see axis_profile.hpp).
  [[nodiscard]] static bool build_axes(const Input<N>& in, const std::array<AxisProfile, kN>& axes,
                                       Synchronization sync, double& common,
                                       std::array<AxisProfile::Built, kN>& built, int& error_axis) noexcept;
  // The prepared axes written: profiles, shortest durations (NaN where not searched, the input kept
  // for axis_min_duration()), blocked intervals, the duration.
  void store(const Input<N>& in, const std::array<AxisProfile, kN>& axes,
             const std::array<AxisProfile::Built, kN>& built, double common) noexcept;
  // A disabled axis as a fresh trajectory has it.
  void clear_axis(std::size_t i) noexcept {
    profiles_[i] = JerkProfile();
    min_duration_[i] = 0.0;
    blocked_count_[i] = 0;
  }
  // Every axis's motion inside its travel (see travel_fit.hpp), or outside_travel naming the axis
  // and the least excess the planner found. `longer` > 0: a time-synchronised axis keeps its travel
  // only with a longer duration than the common one (the caller raises it and rebuilds).
  [[nodiscard]] Result keep_travel(const Input<N>& in, const std::array<AxisLimits, kN>& limits,
                                   const std::array<AxisProfile, kN>& axes, bool planned, int& error_axis,
                                   TravelExcess* excess, double& longer) noexcept;

  // Default-initialised, not value-initialised ({}): that zeroed every profile's unused segment
  // slots on each plan (see JerkSegment).
  std::array<JerkProfile, kN> profiles_;
  // An axis's shortest duration, NaN where calculate() did not need it: axis_min_duration() then
  // searches it from the input kept (one copy of it cost less than gathering each such axis's part).
  std::array<double, kN> min_duration_{};
  Input<N> input_;
  std::array<std::array<Interval, AxisProfile::kMaxBlocked>, kN> blocked_;  // the first blocked_count_ set
  std::array<std::size_t, kN> blocked_count_{};
  AxisArray<N> enabled_{};
  double duration_ = 0.0;
  Synchronization synchronization_ = Synchronization::time;
  std::string_view note_;
};

template <int N>
Result Trajectory<N>::validate(const Input<N>& in, int& axis, std::array<AxisLimits, kN>& limits) noexcept {
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    axis = i;
    // x * 0 is 0 for a finite x and NaN for an infinite or NaN one, so one comparison tests six
    // values (a branch each cost more than the rest of the check, 9 % of a plan from rest).
    const double state = in.current_position[i] * 0.0 + in.current_velocity[i] * 0.0 +
                         in.current_acceleration[i] * 0.0 + in.target_position[i] * 0.0 +
                         in.target_velocity[i] * 0.0 + in.target_acceleration[i] * 0.0;
    if (!(state == 0.0)) return Result::invalid_state;
    const AxisLimits l = limits_of(in, i);
    const double bounds = l.max_velocity * 0.0 + l.min_velocity * 0.0 + l.max_acceleration * 0.0 +
                          l.min_acceleration * 0.0 + l.jerk * 0.0;
    // Nested, not the initializer-list min: that one loops, with a branch per value (which bound is
    // the least is a coin toss).
    const double least = std::min(std::min(std::min(l.max_velocity, -l.min_velocity),
                                           std::min(l.max_acceleration, -l.min_acceleration)),
                                  l.jerk);
    // Every bound finite and > 0; the travel's ends not NaN (infinite: no travel limit) and ordered.
    if (!(bounds == 0.0 && least > 0.0 && in.min_position[i] <= in.max_position[i]))
      return Result::invalid_limits;
    limits[idx(i)] = l;
  }
  axis = -1;
  return Result::working;
}

// Phase synchronisation: true when planned (r says how); false, with the reason in note_, when the
// states are not on a line, the start or the target breaks the limits along it (no note: nothing
// moves at all).
template <int N>
bool Trajectory<N>::plan_phase(const Input<N>& in, const std::array<AxisLimits, kN>& limits, int& error_axis,
                               Result& r) noexcept {
  // The line's direction and the scalar start/target state (progress s, its velocity and acceleration).
  Vector<N> d = Vector<N>::Zero();
  int lead = -1;
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    d[i] = in.target_position[i] - in.current_position[i];
    if (lead < 0 || std::abs(d[i]) > std::abs(d[lead])) lead = i;
  }
  if (lead < 0 || d[lead] == 0.0) {
    // No displacement, no line: time synchronisation, with the note where an axis moves all the same.
    for (int i = 0; i < N; ++i) {
      if (in.enabled[idx(i)] && (in.current_velocity[i] != 0.0 || in.current_acceleration[i] != 0.0 ||
                                 in.target_velocity[i] != 0.0 || in.target_acceleration[i] != 0.0)) {
        note_ = kPhaseFallbackNote;
      }
    }
    return false;
  }
  const double ds = d[lead];
  const MotionState s0{0.0, in.current_velocity[lead] / ds, in.current_acceleration[lead] / ds};
  const MotionState sf{1.0, in.target_velocity[lead] / ds, in.target_acceleration[lead] / ds};
  AxisLimits sl{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity()};
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    // On the line: every axis's state is its displacement times the scalar one.
    const auto on_line = [&](double axis_value, double scalar) {
      return std::abs(axis_value - d[i] * scalar) <= 1e-9 * (1.0 + std::abs(axis_value));
    };
    if (!on_line(in.current_velocity[i], s0.velocity) ||
        !on_line(in.current_acceleration[i], s0.acceleration) ||
        !on_line(in.target_velocity[i], sf.velocity) ||
        !on_line(in.target_acceleration[i], sf.acceleration)) {
      note_ = kPhaseFallbackNote;
      return false;
    }
    if (d[i] == 0.0) continue;
    const AxisLimits& l = limits[idx(i)];
    const double m = std::abs(d[i]);
    const bool forward = d[i] > 0.0;
    sl.max_velocity = std::min(sl.max_velocity, (forward ? l.max_velocity : -l.min_velocity) / m);
    sl.min_velocity = std::max(sl.min_velocity, (forward ? l.min_velocity : -l.max_velocity) / m);
    sl.max_acceleration =
        std::min(sl.max_acceleration, (forward ? l.max_acceleration : -l.min_acceleration) / m);
    sl.min_acceleration =
        std::max(sl.min_acceleration, (forward ? l.min_acceleration : -l.max_acceleration) / m);
    sl.jerk = std::min(sl.jerk, l.jerk / m);
  }
  AxisProfile scalar;
  const AxisStatus st = scalar.plan(s0, sf, sl);
  // The line's bounds come from different axes (one's jerk, another's velocity), so a target every
  // axis can reach on its own may break them (arriving accelerated, the velocity before it): each
  // axis then plans with its own limits.
  if (st == AxisStatus::target_outside_limits) {
    note_ = kPhaseLimitsNote;
    return false;
  }
  if (st != AxisStatus::ok) {
    error_axis = lead;
    r = status_result(st);
    return true;
  }
  // A start beyond the line's limits, whose bounds come from different axes too: its brake along the
  // line, at the line's jerk, could take an axis past its own velocity limit where that axis alone,
  // at its own jerk, keeps it (v 0.009 and a 0.3 on both axes, one of jerk 10, the other of velocity
  // limit 0.01: 0.0135 along the line). Each axis then brakes on its own.
  if (scalar.brake().duration() > 0.0) {
    note_ = kPhaseBrakeNote;
    return false;
  }
  JerkProfile s;
  if (!scalar.build(scalar.min_duration(), s)) {
    error_axis = lead;
    r = Result::unsupported_target;
    return true;
  }
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    JerkProfile& p = profiles_[idx(i)];
    p = JerkProfile(start_of(in, i));
    for (std::size_t k = 0; k < s.size(); ++k) p.append({d[i] * s.segment(k).jerk, s.segment(k).duration});
    min_duration_[idx(i)] = scalar.min_duration();
    blocked_count_[idx(i)] = 0;
  }
  duration_ = scalar.min_duration();
  r = Result::working;
  return true;
}

// From rest to rest on every enabled axis with symmetric limits (every recipe move from a
// standstill, the commonest plan): each axis's shortest duration and its profile in closed form
// (rest_to_rest.hpp), without an AxisProfile, whose general set-up (brake, extremes, blocked
// intervals) was most of such a plan, and straight into `out`, without the scratch copy (its copy
// was a tenth of such a plan): every check is made before `out` is touched. The same durations and
// segments, bit for bit, as the general path gives. False (and `out` as it was) where it does not
// apply or the general path has more to say (a travel that does not hold the start and the target,
// a missed arrival): that path then plans it from the start.
template <int N>
bool Trajectory<N>::plan_rest_to_rest(const Input<N>& in, const std::array<AxisLimits, kN>& limits,
                                      Trajectory& out) noexcept {
  if (in.synchronization == Synchronization::phase) return false;
  double common = 0.0;
  // Only the enabled axes' are set.
  std::array<double, kN> shortest;
  std::array<std::array<JerkSegment, kFarthestJerkSigns.size()>, kN> kept;  // the pieces not empty
  std::array<std::size_t, kN> kept_count;
  std::array<JerkProfile::Reached, kN> reached;
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    // The states first: a moving plan is told at the first axis, for a few instructions.
    if (!(in.current_velocity[i] == 0.0 && in.current_acceleration[i] == 0.0 &&
          in.target_velocity[i] == 0.0 && in.target_acceleration[i] == 0.0)) {
      return false;
    }
    const AxisLimits& l = limits[idx(i)];
    const double from = in.current_position[i];
    const double to = in.target_position[i];
    // Moving only one way (the farthest profile scaled), the motion's positions lie between the start
    // and the target (to rounding, far below keep_travel's slack): the travel holds it if it holds both.
    if (!(l.min_velocity == -l.max_velocity && l.min_acceleration == -l.max_acceleration &&
          in.min_position[i] <= std::min(from, to) && std::max(from, to) <= in.max_position[i])) {
      return false;
    }
    shortest[idx(i)] = rest_to_rest_time(to - from, l);
    common = std::max(common, shortest[idx(i)]);
  }
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    const double T = in.synchronization == Synchronization::none ? shortest[idx(i)] : common;
    const double distance = in.target_position[i] - in.current_position[i];
    const AxisLimits& l = limits[idx(i)];
    std::array<JerkSegment, kFarthestJerkSigns.size()> pieces;
    if (!rest_to_rest_pieces(T, T == shortest[idx(i)], distance, l, pieces)) return false;
    // The states as given (a velocity of -0.0 is at rest too, and integrates as it did there).
    const MotionState start = start_of(in, i);
    JerkProfile::Reached r{start, 0.0};
    std::size_t n = 0;
    for (const JerkSegment& piece : pieces) JerkProfile::keep(kept[idx(i)].data(), n, r, piece);
    const MotionState target = target_of(in, i);
    if (!arrives_at(r.end, target, distance, l)) return false;
    kept_count[idx(i)] = n;
    reached[idx(i)] = r;
  }
  for (int i = 0; i < N; ++i) {
    JerkProfile& p = out.profiles_[idx(i)];
    if (!in.enabled[idx(i)]) {
      out.clear_axis(idx(i));
      continue;
    }
    p.assign_kept(JerkProfile(start_of(in, i)), kept[idx(i)], kept_count[idx(i)], reached[idx(i)]);
    out.min_duration_[idx(i)] = shortest[idx(i)];
    out.blocked_count_[idx(i)] = 0;
  }
  out.enabled_ = in.enabled;
  out.synchronization_ = in.synchronization;
  out.note_ = {};
  out.duration_ = common;
  return true;
}

template <int N>
double Trajectory<N>::longest_min_duration(const Input<N>& in,
                                           const std::array<AxisProfile, kN>& axes) noexcept {
  double common = 0.0;
  int likeliest = -1;  // of the axes whose shortest duration is not known yet
  double guess = -kInf;
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    const AxisProfile& a = axes[idx(i)];
    if (a.min_duration_known() || in.synchronization == Synchronization::none) {
      common = std::max(common, a.min_duration());
      continue;
    }
    // Selected without a branch: which axis guesses longest is a coin toss.
    const double g = a.min_duration_guess();
    likeliest = g > guess ? i : likeliest;
    guess = std::max(g, guess);
  }
  if (likeliest < 0) return common;
  common = std::max(common, axes[idx(likeliest)].min_duration());
  // Each other axis raises it only if it cannot get to its target by then (see reaches_by, asked of
  // every axis: it keeps what prepare() needs); a raise cannot undo an earlier answer (what is
  // reachable at one duration is at every longer one).
  for (int i = 0; i < N; ++i) {
    if (in.enabled[idx(i)] && !axes[idx(i)].reaches_by(common))
      common = std::max(common, axes[idx(i)].min_duration());
  }
  return common;
}

template <int N>
bool Trajectory<N>::build_axes(const Input<N>& in, const std::array<AxisProfile, kN>& axes,
                               Synchronization sync, double& common,
                               std::array<AxisProfile::Built, kN>& built, int& error_axis) noexcept {
  if (sync == Synchronization::time) {
    // Out of every blocked interval; each move to an interval's end can only land in a later one.
    for (int pass = 0; pass <= 2 * N * static_cast<int>(AxisProfile::kMaxBlocked); ++pass) {
      bool moved = false;
      for (int i = 0; i < N; ++i) {
        if (!in.enabled[idx(i)]) continue;
        for (std::size_t b = 0; b < axes[idx(i)].blocked_count(); ++b) {
          if (axes[idx(i)].blocked(b).contains(common)) {
            common = axes[idx(i)].blocked(b).hi;
            moved = true;
          }
        }
      }
      if (!moved) break;
    }
  }
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) continue;
    const AxisProfile& a = axes[idx(i)];
    if (!a.prepare(sync == Synchronization::none ? a.min_duration() : common, built[idx(i)])) {
      error_axis = i;
      return false;
    }
  }
  return true;
}

template <int N>
void Trajectory<N>::store(const Input<N>& in, const std::array<AxisProfile, kN>& axes,
                          const std::array<AxisProfile::Built, kN>& built, double common) noexcept {
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)]) {
      clear_axis(idx(i));
      continue;
    }
    const AxisProfile& a = axes[idx(i)];
    a.write(built[idx(i)], profiles_[idx(i)]);
    // Not searched for (it did not set the duration): kept to be searched if asked.
    min_duration_[idx(i)] = a.min_duration_if_known();
    blocked_count_[idx(i)] = a.blocked_count();
    for (std::size_t b = 0; b < a.blocked_count(); ++b) blocked_[idx(i)][b] = a.blocked(b);
  }
  enabled_ = in.enabled;
  duration_ = common;
  input_ = in;
}

template <int N>
Result Trajectory<N>::keep_travel(const Input<N>& in, const std::array<AxisLimits, kN>& limits,
                                  const std::array<AxisProfile, kN>& axes, bool planned, int& error_axis,
                                  TravelExcess* excess, double& longer) noexcept {
  for (int i = 0; i < N; ++i) {
    if (!in.enabled[idx(i)] || (in.min_position[i] == -kInf && in.max_position[i] == kInf)) continue;
    const double lo = in.min_position[i];
    const double hi = in.max_position[i];
    const double slack = 1e-9 * (1.0 + std::abs(in.target_position[i]));
    JerkProfile& p = profiles_[idx(i)];
    const TravelExcess e = travel_excess(p, lo, hi);
    if (e.by <= slack) continue;
    TravelExcess least = e;  // what the motion the planner could make leaves the travel by
    const auto consider = [&](const TravelExcess& x) {
      if (x.by < least.by) least = x;
      return x.by <= slack;
    };
    // After a phase plan (`planned`) the axes were never planned: only what `!planned` guards first
    // may ask them anything.
    const AxisProfile& a = axes[idx(i)];
    const double T = p.duration();
    const bool at_rest = in.target_velocity[i] == 0.0 && in.target_acceleration[i] == 0.0;
    const bool blended = !planned && synchronization_ == Synchronization::time && T > a.min_duration();
    // A blend at a longer duration than the axis's own: its own shortest motion held at the target.
    if (blended && at_rest) {
      JerkProfile own;
      if (a.build(a.min_duration(), own)) {
        own.append({0.0, std::max(0.0, T - own.duration())});
        if (consider(travel_excess(own, lo, hi))) {
          p = nearest_inside(own, p, lo, hi);
          continue;
        }
      }
    }
    // The fastest turn against the start's velocity, then the shortest motion from there (which end
    // this blend or that shortest motion leaves may differ: the turn is only ever against the velocity).
    JerkProfile turned;
    const MotionState start = start_of(in, i);
    const MotionState target = target_of(in, i);
    if (!planned && turn_first(start, target, limits[idx(i)], start.velocity > 0.0, turned) &&
        consider(travel_excess(turned, lo, hi))) {
      if (synchronization_ == Synchronization::none) {
        p = turned;
        duration_ = std::max(duration_, p.duration());
        continue;
      }
      const double rounding = 1e-12 * (1.0 + T);  // a raised T is the turn's, rebuilt: equal up to rounding
      if (turned.duration() > T + rounding) {
        longer = std::max(longer, turned.duration());
      } else if (at_rest || T - turned.duration() <= rounding) {
        turned.append({0.0, T - turned.duration()});
        p = nearest_inside(turned, p, lo, hi);
        continue;
      }
    }
    error_axis = i;
    if (excess != nullptr) *excess = least;
    return Result::outside_travel;
  }
  return Result::working;
}

template <int N>
Result Trajectory<N>::calculate(const Input<N>& in, Trajectory& out, int& error_axis, TravelExcess* excess,
                                TargetExcess* refusal) noexcept {
  error_axis = -1;
  std::array<AxisLimits, kN> limits;  // only the enabled axes' are set
  if (const Result r = validate(in, error_axis, limits); is_error(r)) return r;
  // Which limit a refused target breaks, and by how much: worked out only once refused.
  const auto refused_target = [&](int i) {
    if (refusal != nullptr) {
      *refusal = target_excess(target_of(in, i), limits[idx(i)]);
    }
  };
  if (plan_rest_to_rest(in, limits, out)) return Result::working;
  std::array<AxisProfile, kN> axes;  // not {}: that zeroed their brakes' unused segment slots
  double common = 0.0;
  // Each axis on its own: its shortest duration and blocked intervals; `common` their maximum.
  const auto plan_axes = [&]() {
    for (int i = 0; i < N; ++i) {
      if (!in.enabled[idx(i)]) continue;
      const MotionState start = start_of(in, i);
      const MotionState target = target_of(in, i);
      const AxisStatus st = axes[idx(i)].plan(start, target, limits[idx(i)]);
      if (st != AxisStatus::ok) {
        error_axis = i;
        if (st == AxisStatus::target_outside_limits) refused_target(i);
        return status_result(st);
      }
    }
    common = longest_min_duration(in, axes);
    if (!std::isfinite(common)) {
      // A search for an axis's shortest duration failed (a safety net: none seen in millions of
      // random problems).
      for (int i = 0; i < N; ++i) {
        if (in.enabled[idx(i)] && axes[idx(i)].min_duration_known() &&
            !std::isfinite(axes[idx(i)].min_duration()))
          error_axis = i;
      }
      return Result::unsupported_target;
    }
    return Result::working;
  };
  std::array<AxisProfile::Built, kN> built;  // only the enabled axes' are set
  // Without a travel to keep, nothing after the build refuses a time- or un-synchronised plan: it goes
  // straight into `out` once every axis is built and has arrived, without the scratch copy.
  if (in.synchronization != Synchronization::phase && !bounded(in)) {
    if (const Result r = plan_axes(); is_error(r)) return r;
    if (!build_axes(in, axes, in.synchronization, common, built, error_axis))
      return Result::unsupported_target;
    out.store(in, axes, built, common);
    out.synchronization_ = in.synchronization;
    out.note_ = {};
    return Result::working;
  }
  // Plan into a scratch copy: a refused plan leaves `out` as it was.
  Trajectory t;
  t.enabled_ = in.enabled;
  t.synchronization_ = in.synchronization;
  bool planned = false;
  if (in.synchronization == Synchronization::phase) {
    Result r = Result::working;
    planned = t.plan_phase(in, limits, error_axis, r);
    if (is_error(r)) return r;
    // Not on a line, or beyond the line's limits: time synchronisation, plan_phase's note saying why
    // (none when nothing moves at all).
    if (!planned) t.synchronization_ = Synchronization::time;
  }
  if (!planned) {
    if (const Result r = plan_axes(); is_error(r)) return r;
  }
  // Built, then checked against the travel; an axis that keeps it only with a longer duration
  // raises the common one, once per axis at most (each raise is its own motion's duration). A
  // straight line that leaves the travel has no other: time synchronisation instead, whose
  // fallbacks (travel_fit.hpp) may keep it, with a note.
  for (int attempt = 0;; ++attempt) {
    if (!planned) {
      if (!build_axes(in, axes, t.synchronization_, common, built, error_axis))
        return Result::unsupported_target;
      t.store(in, axes, built, common);
    }
    double longer = 0.0;
    const Result r = t.keep_travel(in, limits, axes, planned, error_axis, excess, longer);
    if (!is_error(r)) break;
    if (planned) {
      planned = false;
      t.synchronization_ = Synchronization::time;
      t.note_ = kPhaseTravelNote;
      if (const Result p = plan_axes(); is_error(p)) return p;
      attempt = -1;
      continue;
    }
    if (!(longer > common) || attempt >= N) return r;
    common = longer;
  }
  out = t;
  return Result::working;
}

}  // namespace cellctl::planner

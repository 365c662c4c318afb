#include "planner/axis_profile.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <memory>

#include "planner/brake.hpp"
#include "planner/rest_to_rest.hpp"
#include "planner/root_search.hpp"
#include "planner/stop_blend.hpp"

namespace cellctl::planner {
namespace {

// Where g is sampled on [reach, cruise]: evenly, and ever closer to the reach time.
constexpr std::array<double, 16> kSampleAt{0.0,      1.0 / 1024, 1.0 / 256, 1.0 / 128, 1.0 / 64, 1.0 / 32,
                                           1.0 / 16, 1.0 / 8,    2.0 / 8,   3.0 / 8,   4.0 / 8,  5.0 / 8,
                                           6.0 / 8,  7.0 / 8,    15.0 / 16, 1.0};
constexpr int kSamples = static_cast<int>(kSampleAt.size()) - 1;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// From tc (at or after the start of f's cruise) on, f's position grows linearly with `slope`: the
// first duration at which it reaches `target`, given gc = f.position(tc) - target, stepped up an
// ulp at a time if rounding left it just short.
double linear_root(const FarthestProfile& f, double target, double slope, double tc, double gc) noexcept {
  if (gc >= 0.0) return tc;
  double root = tc - gc / slope;
  for (int i = 0; i < 8 && f.position(root) < target; ++i) root = std::nextafter(root, 2.0 * root + 1.0);
  return root;
}

bool target_within(const MotionState& target, const AxisLimits& l) noexcept {
  // At rest, the commonest target, it is within any valid limits (min <= 0 <= max; Trajectory's
  // input check refuses others): without the test's division and comparisons.
  assert(l.min_velocity <= 0.0 && 0.0 <= l.max_velocity && l.min_acceleration <= 0.0 &&
         0.0 <= l.max_acceleration);
  if (target.velocity == 0.0 && target.acceleration == 0.0) return true;
  return std::isfinite(target.velocity) && std::isfinite(target.acceleration) &&
         target_excess(target, l).limit == TargetLimit::none;
}

}  // namespace

AxisStatus AxisProfile::plan(const MotionState& start, const MotionState& target,
                             const AxisLimits& limits) noexcept {
  limits_ = limits;
  blocked_count_ = 0;
  // Nothing of an earlier plan kept, even when this one is refused at once; a refused plan's
  // shortest duration is infinite, at which nothing is built.
  min_known_ = true;
  min_duration_ = kInfinity;
  symmetric_ = false;
  min_side_ = -1;
  constructed_ = {false, false};
  checked_main_ = -1.0;  // no evaluation kept (main durations are >= 0)
  checked_position_ = 0.0;
  if (!target_within(target, limits)) return AxisStatus::target_outside_limits;
  // Every start has a brake into the safe states: none is refused (see brake.hpp). A start at rest
  // needs none (the limits are > 0): not asked, the commonest start.
  if (start.velocity == 0.0 && start.acceleration == 0.0) {
    brake_ = JerkProfile(start);
  } else {
    brake_profile(start, limits, brake_);
  }
  const MotionState s = brake_.end();
  main_start_ = {s.position, std::clamp(s.velocity, limits.min_velocity, limits.max_velocity),
                 std::clamp(s.acceleration, limits.min_acceleration, limits.max_acceleration)};
  target_offset_ = target.position - s.position;
  target_ = target;
  const double v = main_start_.velocity;
  const double a = main_start_.acceleration;
  const bool rest_to_rest = v == 0.0 && a == 0.0 && target.velocity == 0.0 && target.acceleration == 0.0;
  // From rest to rest with symmetric limits (every recipe move, as a rule) the mirrored problem is
  // the same one: the nearest profile is the farthest one negated.
  symmetric_ = rest_to_rest && limits.min_velocity == -limits.max_velocity &&
               limits.min_acceleration == -limits.max_acceleration;
  // The extremes are constructed on first use (extreme()), except to a target at rest, where plan()
  // constructs the one on the target's side of the stop (and the one on the side of the target
  // itself, the same as a rule) below; none symmetric from rest to rest (build() has them in closed
  // form, rest_to_rest_farthest).
  if (rest_to_rest) {
    // From rest to rest: closed form, and never a blocked interval.
    reach_ = 0.0;
    stop_ = Reach{0.0, 0.0, 1.0, 0.0, 0.0, 0.0};  // at rest already: the stop is all hold
    min_duration_ = brake_.duration() + rest_to_rest_time(target_offset_, limits);
    min_side_ = target_offset_ >= 0.0 ? 0 : 1;
    return AxisStatus::ok;
  }
  const bool to_rest = target.velocity == 0.0 && target.acceleration == 0.0;
  // To a target at rest, the extreme on the side the target lies is constructed before the stop: it
  // does not depend on the stop, whose square roots and divisions are the plan's longest chain, so
  // the processor works on both at once. Which extreme is needed is the target's side of the stop,
  // known only once the stop is: the side of the target itself, as a rule (in 96.6 % of the bench's
  // moving starts; the other one is constructed below where it is not).
  const int target_side = target_offset_ < 0.0 ? 1 : 0;
  if (to_rest) static_cast<void>(extreme(static_cast<std::size_t>(target_side)));
  stop_ = to_rest ? stop_to_rest(v, a, limits) : reach(v, a, target.velocity, target.acceleration, limits);
  const Reach& fastest = stop_;
  reach_ = fastest.time;

  const double brake = brake_.duration();
  if (to_rest) {
    // A target at rest can be reached at any duration from the shortest on and then held, so the
    // reachable positions only grow with the duration: no dip on either side. At the reach time
    // they are one point (only one profile gets to rest that fast): the target is beyond it on one
    // side at most, which then falls short until its root. Nor is there a velocity gap after the
    // reach time (one before it ends there), so it is not computed: its end was the reach time up
    // to rounding (the same durations, bit for bit, in 65 million random problems).
    // The search for the first duration at which the extreme on its side gets there is left to
    // min_duration() (settle_min_duration): a synchronised axis may not need it (see reaches_by).
    const double p = fastest.position;
    if (std::isnan(p)) return AxisStatus::unsupported_target;
    min_side_ = p > target_offset_ ? 1 : 0;
    min_duration_ = brake + reach_;
    min_known_ = p == target_offset_;
    // Its extreme is evaluated in every case (reaches_by, prepare): constructed now (as a rule above),
    // so that the test for it later is always passed (after a search it was, without one not: a coin
    // toss).
    if (min_side_ != target_side) static_cast<void>(extreme(static_cast<std::size_t>(min_side_)));
    return AxisStatus::ok;
  }
  // A target acceleration may leave a gap of durations with no way to its velocity and
  // acceleration (see velocity_gap): the search then runs before it (a window) and after it.
  double from = reach_;
  Interval window{};
  bool has_window = false;
  const Gap gap = velocity_gap(v, a, target.velocity, target.acceleration, limits);
  if (gap.hi > gap.lo && gap.hi > reach_) {
    if (gap.lo > reach_) has_window = feasible_window(reach_, gap.lo, window);
    from = gap.hi;
  }
  const ShortSet up = short_set(extreme(0), target_offset_, limits.max_velocity, from);
  const ShortSet down = short_set(extreme(1), -target_offset_, -limits.min_velocity, from);
  double t = from;
  for (const ShortSet* s2 : {&up, &down}) {
    if (s2->gap) return AxisStatus::unsupported_target;
    if (s2->from_reach) t = std::max(t, s2->end);
  }
  // The shortest duration may land in the other side's dip: it then starts after the dip.
  for (int pass = 0; pass < 2; ++pass) {
    for (const ShortSet* s2 : {&up, &down}) {
      if (s2->dip && t > s2->dip_lo && t < s2->dip_hi) t = s2->dip_hi;
    }
  }
  min_duration_ = brake + t;
  if (has_window) {
    min_duration_ = brake + window.lo;
    blocked_[blocked_count_++] = {brake + window.hi, brake + t};
  }
  for (const ShortSet* s2 : {&up, &down}) {
    if (s2->dip && s2->dip_lo >= t) blocked_[blocked_count_++] = {brake + s2->dip_lo, brake + s2->dip_hi};
  }
  std::sort(blocked_.begin(), blocked_.begin() + static_cast<std::ptrdiff_t>(blocked_count_),
            [](const Interval& x, const Interval& y) { return x.lo < y.lo; });
  if (!std::isfinite(min_duration_)) return AxisStatus::unsupported_target;
  if (target.acceleration != 0.0) {
    JerkProfile check;
    if (!build(min_duration_, check)) return AxisStatus::unsupported_target;
  }
  return AxisStatus::ok;
}

const FarthestProfile& AxisProfile::extreme(std::size_t side) const noexcept {
  if (!constructed_[side]) {
    // Constructed in place: one built elsewhere and copied in is read back with wide loads straight
    // after its narrow stores, a stalled store forward per piece.
    // Side 1 is the mirrored frame; which side is data (a coin toss to a target at rest), so it is
    // not branched on.
    const double sign = 1.0 - 2.0 * static_cast<double>(side);
    const std::array<AxisLimits, 2> frame{limits_, limits_.mirrored()};
    std::construct_at(&extremes_[side], sign * main_start_.velocity, sign * main_start_.acceleration,
                      sign * target_.velocity, sign * target_.acceleration, frame[side]);
    constructed_[side] = true;
  }
  return extremes_[side];
}

bool AxisProfile::feasible_window(double lo, double hi, Interval& window) const noexcept {
  // Both extremes are one profile at both ends (only one way to the target's velocity and
  // acceleration there), so the window, if any, lies inside: samples crowd towards both ends.
  const auto h = [&](double T) { return margin(T); };
  std::array<double, 2 * kSampleAt.size() - 1> at{};
  for (std::size_t k = 0; k < kSampleAt.size(); ++k) {
    at[k] = lo + (hi - lo) * kSampleAt[k] / 2.0;
    at[at.size() - 1 - k] = hi - (hi - lo) * kSampleAt[k] / 2.0;
  }
  std::array<double, at.size()> hs{};
  std::size_t first = at.size();
  std::size_t last = 0;
  for (std::size_t k = 0; k < at.size(); ++k) {
    hs[k] = h(at[k]);
    if (hs[k] >= 0.0) {
      first = std::min(first, k);
      last = k;
    }
  }
  if (first == at.size()) {
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      if (narrow_window(at[k], at[k + 1], window)) return true;
    }
    return false;
  }
  window.lo = first == 0 ? at[0] : find_root(h, at[first - 1], at[first], false);
  window.hi = last + 1 == at.size() ? at[last] : find_root(h, at[last], at[last + 1], true);
  return true;
}

bool AxisProfile::narrow_window(double a, double b, Interval& window) const noexcept {
  // Where the target crosses the middle of the reachable positions it is inside them (their width
  // is >= 0), however briefly: seed 4 problem 4547520 had a window of 1e-3 s between samples
  // 4e-3 s apart. At both ends of the range the extremes are one profile, so a target on different
  // sides of it there is crossed for certain.
  const auto middle = [&](double T) {
    return extreme(0).position(T) - extreme(1).position(T) - 2.0 * target_offset_;
  };
  const double ma = middle(a);
  const double mb = middle(b);
  if (!(ma >= 0.0 && mb < 0.0) && !(ma < 0.0 && mb >= 0.0)) return false;  // no crossing (or NaN)
  const double crossing = find_root(middle, a, b, ma >= 0.0);
  // A band no wider than rounding there is no window.
  if (!(margin(crossing) >= 0.0)) return false;
  const auto h = [&](double T) { return margin(T); };
  window.lo = find_root(h, a, crossing, false);
  window.hi = find_root(h, crossing, b, true);
  return true;
}

double AxisProfile::margin(double T) const noexcept {
  const double up = extreme(0).position(T) - target_offset_;
  const double down = extreme(1).position(T) + target_offset_;
  return std::isnan(up) || std::isnan(down) ? -kInfinity : std::min(up, down);
}

AxisProfile::ShortSet AxisProfile::short_set(const FarthestProfile& f, double target, double slope,
                                             double t0) const noexcept {
  ShortSet set;
  // A duration with no extreme profile (possible only with a target acceleration) makes the
  // search unreliable: the plan is then refused rather than trusted.
  const auto g = [&](double T) {
    const double p = f.position(T);
    if (std::isnan(p)) set.gap = true;
    return p - target;
  };
  const double tc = std::max(f.cruise_from(), t0);
  const double g0 = g(t0);
  if (set.gap) return set;
  if (tc - t0 <= 1e-15 * tc) {
    // Cruising from t0 on: linear, one root at most.
    if (g0 < 0.0) {
      set.from_reach = true;
      set.end = linear_root(f, target, slope, tc, g(tc));
    }
    return set;
  }
  // g need not be monotonic nor convex on [t0, tc]: sample it. Short at the reach time, the set
  // starts there and ends at the first root (bracketed by the first sample that is not short); the
  // rest of the range may still hold a dip (falling short again before the cruise makes up). The
  // first root can sit just after the reach time with a dip right behind it (the extremes part from
  // one profile there): the samples crowd towards it.
  std::array<double, kSampleAt.size()> at{};
  std::array<double, kSampleAt.size()> gs{};
  for (std::size_t k = 0; k < kSampleAt.size(); ++k) {
    at[k] = k == kSamples ? tc : t0 + (tc - t0) * kSampleAt[k];
    gs[k] = k == 0 ? g0 : g(at[k]);
  }
  if (set.gap) return set;
  int first = 0;  // the first sample that is not short
  double left = t0;
  if (g0 < 0.0) {
    set.from_reach = true;
    while (first <= kSamples && gs[static_cast<std::size_t>(first)] < 0.0) ++first;
    // Short at every sample before `first`, the target may still be reached between two of them: g
    // can rise above zero and fall short again there (seed 12 problem 313190 of the accelerating
    // targets: 2.6e-4 m above it for 0.025 s, between samples). The highest sample above both its
    // neighbours is refined (golden section, unimodal there); a bump that reaches zero ends the set
    // at its first root, and the short stretch after it, to the first root bracketed, is a dip.
    int peak = -1;
    for (int k = 1; k < first && k < kSamples; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (gs[i] >= gs[i - 1] && gs[i] >= gs[i + 1] &&
          (peak < 0 || gs[i] > gs[static_cast<std::size_t>(peak)]))
        peak = k;
    }
    if (peak >= 0) {
      const auto i = static_cast<std::size_t>(peak);
      const double top = golden_minimum([&](double T) { return -g(T); }, at[i - 1], at[i + 1], 0.0);
      if (set.gap) return set;
      if (g(top) >= 0.0) {
        set.end = find_root(g, at[i - 1], top, false);
        set.dip = true;
        set.dip_lo = find_root(g, top, at[i + 1], true);
        set.dip_hi = first > kSamples ? linear_root(f, target, slope, tc, gs[kSamples])
                                      : find_root(g, at[static_cast<std::size_t>(first) - 1],
                                                  at[static_cast<std::size_t>(first)], false);
        return set;
      }
    }
    if (first > kSamples) {
      set.end = linear_root(f, target, slope, tc, gs[kSamples]);
      return set;
    }
    const auto i = static_cast<std::size_t>(first);
    left = find_root(g, at[i - 1], at[i], false);
    set.end = left;
  }
  // An extreme profile that never moves backwards only gains from more time: no dip.
  {
    SevenDurations d{};
    if (f.durations(left, d) && f.lowest_velocity_of(d) >= 0.0) return set;
  }
  // The lowest sample after `left`, and the lowest one below both its neighbours: the lowest can
  // be the first (g starts near zero at the reach time) with the dip between two later samples
  // (seed 3 problem 507850 of the accelerating targets, 0.07 s wide between samples 0.12 s apart).
  // If no sample is short, their neighbourhoods are refined (golden-section searches, unimodal there).
  int lowest = first;
  int valley = -1;
  for (int k = first + 1; k <= kSamples; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (gs[i] < gs[static_cast<std::size_t>(lowest)]) lowest = k;
    if (k < kSamples && gs[i] <= gs[i - 1] && gs[i] <= gs[i + 1] &&
        (valley < 0 || gs[i] < gs[static_cast<std::size_t>(valley)])) {
      valley = k;
    }
  }
  // A dip no deeper than rounding is none: a profile inside it would miss the target by less than
  // the arrival tolerance, and its ends would be noise.
  const double shallow = -1e-12 * (1.0 + std::abs(target));
  double t_min = at[static_cast<std::size_t>(lowest)];
  if (!(gs[static_cast<std::size_t>(lowest)] < shallow)) {
    bool found = false;
    for (const int k : {lowest, valley == lowest ? -1 : valley}) {
      if (found || k < 0) continue;
      const auto i = static_cast<std::size_t>(k);
      const double lo = k > first ? at[i - 1] : left;
      const double hi = k < kSamples ? at[i + 1] : tc;
      t_min = golden_minimum(g, std::max(lo, left), hi, shallow);
      if (set.gap) return set;
      found = g(t_min) < shallow;
    }
    // A dip can also lie between two samples that both rise, behind a crest between the ones before
    // (seed 4 problem 1088174 of the accelerating targets: g rises from its root at 0.316 s to a crest
    // at 0.35 s, falls 2.7e-4 m short from 0.419 s to 0.477 s, and the samples at 0.318, 0.409 and
    // 0.590 s all rise). A sample where g falls has a minimum after it, before the next sample
    // that is higher: refined the same way.
    for (int k = first; !found && k < kSamples; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (!(gs[i + 1] > gs[i])) continue;  // falling on to the next sample: `lowest` and `valley` cover it
      double rate = 0.0;                   // g's slope at the sample
      if (std::isnan(f.position_and_slope(at[i], rate)) || !(rate < 0.0)) continue;
      t_min = golden_minimum(g, std::max(at[i], left), at[i + 1], shallow);
      if (set.gap) return set;
      found = g(t_min) < shallow;
    }
    if (!found) return set;
  }
  // The dip's ends: the last non-short point before t_min, the first after it.
  double lo_end = left;
  for (int k = first; k <= kSamples && at[static_cast<std::size_t>(k)] < t_min; ++k) {
    if (gs[static_cast<std::size_t>(k)] >= 0.0) lo_end = std::max(lo_end, at[static_cast<std::size_t>(k)]);
  }
  int after = kSamples + 1;
  for (int k = kSamples; k >= first && at[static_cast<std::size_t>(k)] > t_min; --k) {
    if (gs[static_cast<std::size_t>(k)] >= 0.0) after = k;
  }
  set.dip = true;
  set.dip_lo = find_root(g, lo_end, t_min, true);
  set.dip_hi = after <= kSamples ? find_root(g, t_min, at[static_cast<std::size_t>(after)], false)
                                 : linear_root(f, target, slope, tc, gs[kSamples]);
  return set;
}

double AxisProfile::shortest(const FarthestProfile& f, double target, double slope, double t0,
                             double g0) const noexcept {
  const double tc = std::max(f.cruise_from(), t0);
  const double gc = f.position(tc) - target;
  if (gc < 0.0 || tc - t0 <= 1e-15 * tc) return linear_root(f, target, slope, tc, gc);
  // Over the peak velocity first: a Newton step there is a few multiplications, one over T below
  // solves the extreme's case of active bounds first (the search for the shortest duration took
  // about 560 instructions per axis of a moving start, now about 310).
  if (const double fast = f.duration_to_rest(target); fast >= t0 && fast <= tc) return fast;
  bool gap = false;
  const auto g = [&](double T, double& s) {
    const double p = f.position_and_slope(T, s);
    gap = gap || std::isnan(p);
    return p - target;
  };
  // Newton from the tangent at the cruise's start: before it the farthest position is convex as a
  // rule (the closer the profile comes to cruising, the more it gains from more time), so the steps
  // stay on the feasible side and end there (about four evaluations, regula falsi took sixteen).
  const double root = newton_root(g, t0, g0, tc, gc, tc - gc / slope);
  return gap ? kInfinity : root;
}

bool AxisProfile::feasible(double T) const noexcept {
  if (T < min_duration()) return false;
  for (std::size_t i = 0; i < blocked_count_; ++i) {
    if (blocked_[i].contains(T)) return false;
  }
  return true;
}

void AxisProfile::settle_min_duration() const noexcept {
  // In the frame of the target's side (mirrored for side 1), without a branch on which it is.
  const auto side = static_cast<std::size_t>(min_side_);
  const double sign = 1.0 - 2.0 * static_cast<double>(side);
  const std::array<double, 2> speed{limits_.max_velocity, -limits_.min_velocity};
  const double t = shortest(extreme(side), sign * target_offset_, speed[side], reach_,
                            sign * (stop_.position - target_offset_));
  // A failed search (NaN as well as +infinity) is +infinity: no plan can be built at it, and a NaN
  // would be lost in the maximum of the axes' durations.
  min_duration_ = std::isfinite(t) ? brake_.duration() + t : kInfinity;
  min_known_ = true;
}

bool AxisProfile::reaches_by(double T) const noexcept {
  // To a target at rest (not from rest to rest with symmetric limits, which prepare() does in
  // closed form) the extreme is evaluated whether the shortest duration is known or not: prepare()
  // at T then takes it, whichever axis set T (branching on that cost a coin toss per axis).
  if (min_side_ < 0 || symmetric_) return min_duration_ <= T;
  // In the mirrored frame (side 1) the target is at -target_offset_.
  const auto side = static_cast<std::size_t>(min_side_);
  const double target = (1.0 - 2.0 * static_cast<double>(side)) * target_offset_;
  checked_main_ = std::max(T - brake_.duration(), reach_);
  checked_position_ = extreme(side).position(checked_main_, checked_);
  // With a margin above rounding: within a few ulps of the search's root the evaluation and the
  // search can disagree (helper 24 found 32 559 of 12.8 million durations 1 to 64 ulps below the
  // searched one that reached), and the common duration would then end below this axis's own. A
  // near tie is left to the search.
  const double margin = 1e-12 * (1.0 + std::abs(target));
  const std::array<bool, 2> answer{checked_position_ >= target + margin, min_duration_ <= T};
  return answer[min_known_ ? 1 : 0];
}

double AxisProfile::min_duration_guess() const noexcept {
  // Indexed, not branched on: which side the target lies is a coin toss.
  const std::array<double, 2> speed_of{limits_.max_velocity, -limits_.min_velocity};
  const double speed = speed_of[static_cast<std::size_t>(min_side_)];
  return min_duration_ + std::abs(target_offset_ - stop_.position) / speed;
}

bool AxisProfile::build(double T, JerkProfile& out) const noexcept {
  Built built;
  if (!prepare(T, built)) return false;
  write(built, out);
  return true;
}

bool AxisProfile::prepare(double T, Built& built) const noexcept {
  // The pieces as JerkProfile::append() takes them (empty ones dropped), integrated from the brake's
  // end in the same order: the same end state, bit for bit, with the state kept in registers.
  std::size_t n = 0;
  JerkProfile::Reached r{brake_.end(), brake_.duration()};
  const auto add = [&](double jerk, double duration) {
    JerkProfile::keep(built.pieces.data(), n, r, {jerk, duration});
  };
  const auto done = [&] {
    built.n = n;
    built.reached = r;
    return arrives_at(r.end, target_, target_offset_, limits_);
  };
  // An infinite T is a failed search for the shortest duration (min_duration()): no profile.
  if (!std::isfinite(T)) return false;
  const double main = std::max(T - brake_.duration(), reach_);
  if (symmetric_) {
    // From rest to rest with symmetric limits: in closed form (rest_to_rest.hpp).
    std::array<JerkSegment, kFarthestJerkSigns.size()> pieces;
    if (!rest_to_rest_pieces(main, T == min_duration_, target_offset_, limits_, pieces)) return false;
    for (const JerkSegment& p : pieces) add(p.jerk, p.duration);
    return done();
  }
  const double j = limits_.jerk;
  // Not zeroed: position() sets all seven (or says NaN, and they are not used).
  SevenDurations up;
  SevenDurations down;
  if (min_side_ >= 0) {
    // A target at rest. Its extreme profile on the target's side gets at least as far as the target
    // at every duration from the shortest on (a target at rest has no dip: what is reachable at one
    // duration is, held at rest, at every longer one); the fastest stop held at rest ends at the
    // reach position p, on the other side of the target (so min_side_ was chosen), or on it. Both
    // are profiles of duration T from the same start within the limits ending at rest, and the
    // states reachable at T are a convex set with the dynamics linear in the jerk: a convex blend of
    // their jerks keeps the limits and ends at rest, at the blend of their positions. So the share
    // of the extreme that ends on the target is (target - p) / (extreme - p), 0 where p is the
    // target (stop and hold). The other extreme is then not needed: with its construction, its
    // evaluation at T and the merge of two 7-segment sequences prepare() took about 830
    // instructions per axis of a moving 3-DoF plan, with the stop about 525.
    const auto side = static_cast<std::size_t>(min_side_);
    const double sign = 1.0 - 2.0 * static_cast<double>(side);  // not a branch: which side is data
    // Evaluated already where reaches_by() checked this duration.
    const SevenDurations* at = &checked_;
    double position = checked_position_;
    if (main != checked_main_) {
      position = extreme(side).position(main, up);
      at = &up;
    }
    const SevenDurations& d = *at;
    const double reached = sign * position;
    // The pieces are not integrated again (that was 11 % of a moving plan's instructions): the
    // dynamics are linear in the jerk, so the extreme ends where its evaluation did, and the blend
    // in the blend of that end and the stop's, at p + share * width. The evaluation checked that
    // the extreme's durations, solved case by case, end at rest (else its position is NaN); the
    // stop and the cruise are closed forms, and both end at rest to rounding (the tests integrate
    // every profile's segments). So the arrival check here is on the position alone, and the
    // profile's stated end is the target's state.
    const auto at_target = [&] {
      built.n = n;
      built.reached = {target_, r.time};
    };
    // The shortest duration is the extreme profile itself: no blend (whose share of the stop would
    // only be rounding). Unless that profile misses the target by more than rounding (the shortest
    // duration lies a few ulps past the root; where the position's slope is steep, 2 in 10^5 problems
    // missed by 1e-11 m): the blend then ends on the target. The test is the arrival check, tighter.
    if (min_known_ && T == min_duration_ &&
        std::abs(reached - target_offset_) <= 1e-13 * (1.0 + std::abs(target_offset_))) {
      for (std::size_t i = 0; i < d.size(); ++i) {
        JerkProfile::keep_timed(built.pieces.data(), n, r.time, {sign * kFarthestJerkSigns[i] * j, d[i]});
      }
      at_target();
      return true;
    }
    if (!std::isnan(reached)) {
      const double p = stop_.position;
      const double width = reached - p;
      const double share = width != 0.0 ? std::clamp((target_offset_ - p) / width, 0.0, 1.0) : 0.0;
      blend_with_stop(d, share * sign * j, stop_, (1.0 - share) * stop_.direction * j, built.pieces, n,
                      r.time);
      at_target();
      return std::abs(p + share * width - target_offset_) <= 1e-9 * (1.0 + std::abs(target_offset_));
    }
  }
  const double far = extreme(0).position(main, up);
  const double near = -extreme(1).position(main, down);
  const bool has_up = !std::isnan(far);
  const bool has_down = !std::isnan(near);
  if (!has_up && !has_down) return false;
  // The share of the farthest profile's jerk in the blend that ends exactly at the target.
  double share = 1.0;
  if (!has_up) {
    share = 0.0;
  } else if (has_down && far - near > 0.0) {
    share = std::clamp((target_offset_ - near) / (far - near), 0.0, 1.0);
  }
  if (share == 1.0 || share == 0.0) {
    const bool use_up = share == 1.0;
    const SevenDurations& d = use_up ? up : down;
    const double sign = use_up ? 1.0 : -1.0;
    for (std::size_t i = 0; i < d.size(); ++i) add(sign * kFarthestJerkSigns[i] * j, d[i]);
  } else {
    // Merge the two switching sequences; in each piece the jerk is the blend of both.
    std::size_t iu = 0;
    std::size_t id = 0;
    std::size_t merged = 0;
    double left_u = up[0];
    double left_d = down[0];
    while (iu < up.size() && id < down.size() && merged < built.pieces.size()) {
      const double piece = std::min(left_u, left_d);
      add(j * (share * kFarthestJerkSigns[iu] - (1.0 - share) * kFarthestJerkSigns[id]), piece);
      ++merged;
      left_u -= piece;
      left_d -= piece;
      if (left_u <= 0.0 && ++iu < up.size()) left_u = up[iu];
      if (left_d <= 0.0 && ++id < down.size()) left_d = down[id];
    }
  }
  return done();
}

}  // namespace cellctl::planner

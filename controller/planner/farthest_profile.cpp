#include "planner/farthest_profile.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "planner/jerk_profile.hpp"
#include "planner/root_search.hpp"

namespace cellctl::planner {
namespace {

// The free quantities of one case of active bounds (or their derivatives with respect to T).
struct Levels {
  double a1, t2, a3, t6;
};

// The shortest velocity change (a0 -> peak >= max(a0, af) -> af) from v0 to vf: its peak and
// how long that is held (at a_cap, when the peak would exceed it), and its duration; an infinite
// duration when this shape cannot do it. `inv_j` is 1 / j: a division takes several
// multiplications' time, and the stop is on the way to every later step of a plan (its four
// divisions were 2-3 % of a moving plan's time).
struct Rise {
  double peak = 0.0;
  double hold = 0.0;
  double time = std::numeric_limits<double>::infinity();
};
[[gnu::always_inline]] inline Rise rise(double v0, double a0, double vf, double af, double a_cap, double j,
                                        double inv_j) noexcept {
  const double dv = vf - v0;
  const double floor_peak = std::max(a0, af);
  const double x = (2.0 * j * dv + a0 * a0 + af * af) / 2.0;
  const double tol = 1e-12 * (std::abs(a0) + std::abs(af) + a_cap);
  if (x < -tol * tol * 1e12) return {};
  const double r = std::sqrt(std::max(x, 0.0));
  Rise rise;
  if (-r >= floor_peak - tol) {
    rise.peak = std::max(-r, floor_peak);  // both ends below zero and the change small: peak below zero
  } else if (r >= floor_peak - tol) {
    rise.peak = std::max(r, floor_peak);
  } else {
    return {};
  }
  if (rise.peak > a_cap) {
    rise.peak = a_cap;
    rise.hold = std::max(0.0, (dv - (2.0 * a_cap * a_cap - a0 * a0 - af * af) * (0.5 * inv_j)) / a_cap);
  }
  rise.time = (2.0 * rise.peak - a0 - af) * inv_j + rise.hold;
  return rise;
}

// The reach profile made by a rise from (v0, a0) to (vf, af), all four given in the frame
// `direction` (1 ours, -1 mirrored), and the distance it covers, in ours. Each piece's distance is
// taken from a state known without the pieces before it (the ramp in from the start, the ramp out
// from the end, the hold from the velocities at both its ends), and the three are summed: the stop's
// position is on the way to every later step of a plan, and integrated piece after piece it was a
// chain of about 70 cycles.
[[gnu::always_inline]] inline Reach reach_by(const Rise& rise, double v0, double a0, double vf, double af,
                                             double j, double inv_j, double direction) noexcept {
  const double ramp_in = (rise.peak - a0) * inv_j;
  const double ramp_out = (rise.peak - af) * inv_j;
  const double hold = rise.hold;
  const double sixth = j * (1.0 / 6.0);
  const double in = ramp_in * (v0 + ramp_in * (a0 * 0.5 + ramp_in * sixth));
  const double out = ramp_out * (vf - ramp_out * (af * 0.5 + ramp_out * sixth));
  const double held_from = v0 + ramp_in * (a0 + ramp_in * (0.5 * j));
  const double held_to = vf - ramp_out * (af + ramp_out * (0.5 * j));
  const double held = hold * (0.5 * (held_from + held_to));
  return {rise.time, direction * ((in + out) + held), direction, ramp_in, hold, ramp_out};
}

// The gap for a0, af >= 0 (see velocity_gap): dv the velocity change, amin < 0.
Gap gap_above_zero(double a0, double af, double dv, double amin, double j) noexcept {
  const double d = (a0 * a0 + af * af - 2.0 * j * dv) / 2.0;
  if (!(d > 0.0)) return {};
  const double m = std::sqrt(d);
  Gap gap;
  gap.lo = m < std::min(a0, af) ? (a0 + af - 2.0 * m) / j : 0.0;
  if (-m >= amin) {
    gap.hi = (a0 + af + 2.0 * m) / j;
  } else {
    const double at_floor = (a0 * a0 + af * af - 2.0 * amin * amin) / (2.0 * j);
    gap.hi = (a0 + af - 2.0 * amin) / j + (dv - at_floor) / amin;
  }
  return gap;
}

}  // namespace

Gap velocity_gap(double v0, double a0, double vf, double af, const AxisLimits& limits) noexcept {
  const double j = limits.jerk;
  if (a0 >= 0.0 && af >= 0.0) return gap_above_zero(a0, af, vf - v0, limits.min_acceleration, j);
  if (a0 <= 0.0 && af <= 0.0) return gap_above_zero(-a0, -af, v0 - vf, -limits.max_acceleration, j);
  return {};
}

namespace {

// reach() and stop_to_rest() in one: stop_to_rest() is it with the target's zeros known to the
// compiler.
[[gnu::always_inline]] inline Reach reach_in(double v0, double a0, double vf, double af,
                                             const AxisLimits& limits) noexcept {
  const double j = limits.jerk;
  const double inv_j = 1.0 / j;
  const Rise up = rise(v0, a0, vf, af, limits.max_acceleration, j, inv_j);
  const Rise down = rise(-v0, -a0, -vf, -af, -limits.min_acceleration, j, inv_j);
  if (down.time < up.time) return reach_by(down, -v0, -a0, -vf, -af, j, inv_j, -1.0);
  if (std::isinf(up.time)) return {up.time, std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0, 0.0, 0.0};
  return reach_by(up, v0, a0, vf, af, j, inv_j, 1.0);
}

}  // namespace

Reach reach(double v0, double a0, double vf, double af, const AxisLimits& limits) noexcept {
  return reach_in(v0, a0, vf, af, limits);
}

Reach stop_to_rest(double v0, double a0, const AxisLimits& limits) noexcept {
  // Which way the fastest stop goes is the sign of J v_r, v_r the velocity at which ramping the
  // acceleration out at once leaves the axis (v0 + a0 |a0| / 2J): above zero only the fall (down)
  // can stop it, below only the rise (up). rise() finds the other one infinite there, by its own
  // tolerance tol = 1e-12 s (s = |a0| + its acceleration bound): with x = a0^2 / 2 - J v0 its
  // square, a0 > 0 leaves it below (a0 - tol)^2 once J v_r > 4 tol (a0 + tol), a0 <= 0 below
  // -1e12 tol^2 once J v_r > 1e12 tol^2; both are below 1.1e-11 s^2, s taken with the larger bound
  // (so at least either rise's). Past that only the one that can stop is computed: the same values,
  // bit for bit, and one rise instead of two (whichever is faster was a coin toss too). Nearer the
  // curve v_r = 0, and for NaN, both, as reach() does.
  const double j = limits.jerk;
  const double a0_abs = std::abs(a0);
  const double drift = j * v0 + 0.5 * a0 * a0_abs;
  const double s = a0_abs + std::max(limits.max_acceleration, -limits.min_acceleration);
  if (!(std::abs(drift) > 1.1e-11 * s * s)) return reach_in(v0, a0, 0.0, 0.0, limits);
  const double sign = std::copysign(1.0, -drift);  // down (mirrored) where it must fall
  const double cap = drift > 0.0 ? -limits.min_acceleration : limits.max_acceleration;
  const double zero = sign * 0.0;  // the target at rest in the stop's frame, -0.0 mirrored as in reach()
  const double inv_j = 1.0 / j;
  const Rise r = rise(sign * v0, sign * a0, zero, zero, cap, j, inv_j);
  if (std::isinf(r.time)) return {r.time, std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0, 0.0, 0.0};
  return reach_by(r, sign * v0, sign * a0, zero, zero, j, inv_j, sign);
}

FarthestProfile::FarthestProfile(double v0, double a0, double vf, double af,
                                 const AxisLimits& limits) noexcept
    : v0_(v0), a0_(a0), vf_(vf), af_(af), lim_(limits) {
  const double j = lim_.jerk;
  inv_jerk_ = 1.0 / j;
  const double amax = lim_.max_acceleration;
  const double amin = lim_.min_acceleration;
  const double vmax = lim_.max_velocity;
  SevenDurations& t = cruise_shape_;  // each set once below (not zeroed first)
  t[3] = 0.0;
  // Up to (max_velocity, 0): +J to a1 = sqrt(x), hold, -J to 0. (Where the level is capped, as in
  // most long moves, its root is not needed.)
  const double rise = vmax - v0;
  const double x1 = (2.0 * j * rise + a0 * a0) / 2.0;
  if (x1 <= amax * amax) {
    const double a1 = std::max(std::sqrt(std::max(0.0, x1)), std::max(a0, 0.0));
    t[0] = (a1 - a0) * inv_jerk_;
    t[1] = 0.0;
    t[2] = a1 * inv_jerk_;
  } else {
    t[0] = (amax - a0) * inv_jerk_;
    t[1] = std::max(0.0, (rise - (2.0 * amax * amax - a0 * a0) * 0.5 * inv_jerk_) / amax);
    t[2] = amax * inv_jerk_;
  }
  // Down from (max_velocity, 0) to (vf, af): -J to a3 = -sqrt(x), hold, +J to af.
  const double fall = vmax - vf;
  const double x3 = (2.0 * j * fall + af * af) / 2.0;
  if (x3 <= amin * amin) {
    const double a3 = std::min(-std::sqrt(std::max(0.0, x3)), std::min(af, 0.0));
    t[4] = -a3 * inv_jerk_;
    t[5] = 0.0;
    t[6] = (af - a3) * inv_jerk_;
  } else {
    t[4] = -amin * inv_jerk_;
    t[5] = std::max(0.0, (fall - (2.0 * amin * amin - af * af) * 0.5 * inv_jerk_) / -amin);
    t[6] = (af - amin) * inv_jerk_;
  }
  double from = 0.0;  // summed in a local: a member store per term otherwise (t may alias it)
  for (const double d : t) from += d;
  cruise_from_ = from;
  half_jerk_ = j / 2.0;
  sixth_jerk_ = j * (1.0 / 6.0);  // a multiplication, not a division (see Rise)
  // The end position at cruise_from_: each piece's distance from a state known without the pieces
  // before it (the rise's first two from the start, its last ramp and the fall's first two from
  // (max_velocity, 0), the fall's last from (vf, af)), summed side by side, as in reach_by().
  const double half = half_jerk_;
  const double sixth = sixth_jerk_;
  const double a1 = a0 + j * t[0];
  const double v1 = v0 + t[0] * (a0 + t[0] * half);
  const double d0 = t[0] * (v0 + t[0] * (a0 * 0.5 + t[0] * sixth));
  const double d1 = t[1] * (v1 + t[1] * (a1 * 0.5));
  const double d2 = t[2] * (vmax - t[2] * t[2] * sixth);
  const double d4 = t[4] * (vmax - t[4] * t[4] * sixth);
  const double v4 = vmax - t[4] * t[4] * half;
  const double d5 = t[5] * (v4 - t[5] * (j * t[4] * 0.5));
  const double d6 = t[6] * (vf - t[6] * (af * 0.5 - t[6] * sixth));
  cruise_position_ = ((d0 + d1) + d2) + ((d4 + d5) + d6);
}

bool FarthestProfile::durations(double T, SevenDurations& t, SevenDurations* rates) const noexcept {
  if (T >= cruise_from_) {
    t = cruise_shape_;
    t[3] = T - cruise_from_;
    if (rates != nullptr) *rates = SevenDurations{0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    return true;
  }
  return no_cruise(T, t, rates);
}

bool FarthestProfile::peak_within_velocity(double a1, double t2) const noexcept {
  const double j = lim_.jerk;
  const double v1 = v0_ + (a1 * a1 - a0_ * a0_) / (2.0 * j) + a1 * t2;
  const double peak = v1 + a1 * a1 / (2.0 * j);
  return peak <= lim_.max_velocity * (1.0 + 1e-12) + 1e-12;
}

bool FarthestProfile::no_cruise(double T, SevenDurations& t, SevenDurations* rates) const noexcept {
  const double j = lim_.jerk;
  const double amax = lim_.max_acceleration;
  const double amin = lim_.min_acceleration;
  const double a0 = a0_;
  const double af = af_;
  const double dv = vf_ - v0_;
  // Near the reach time the levels are ill-conditioned (a tiny S divides): generous, then clamped.
  const double tol_a = 1e-8 * (amax - amin);
  const double tol_t = 1e-12 * (T + (amax - amin) / j);
  // A double root (the held level equals the start or end level) comes out a rounding below zero.
  const double tol_disc = 1e-12 * (amax - amin) * (amax - amin);

  // One set of active bounds: peak level a1 (held t2), low level a3 (held t6); checks and fills t.
  // `rate` gives the derivatives of (a1, t2, a3, t6) with respect to T in this case; it is only
  // called when `rates` is wanted (it may divide by a root that is zero at the case's edge).
  const auto accept = [&](double a1, double t2, double a3, double t6, const auto& rate) {
    if (!(a1 >= a0 - tol_a && a1 <= amax + tol_a && a3 <= af + tol_a && a3 >= amin - tol_a &&
          a3 <= a1 + tol_a && t2 >= -tol_t && t6 >= -tol_t)) {
      return false;
    }
    a1 = std::clamp(a1, a0, amax);
    a3 = std::clamp(a3, amin, std::min(af, a1));
    t2 = std::max(t2, 0.0);
    t6 = std::max(t6, 0.0);
    const double t1 = (a1 - a0) * inv_jerk_;
    double t3 = (a1 - a3) * inv_jerk_;
    const double t7 = (af - a3) * inv_jerk_;
    // What T leaves over these durations: rounding, or what the clamping moved.
    const double left = T - t1 - t2 - t3 - t6 - t7;
    if (t3 + left < -tol_t) return false;
    // A hold takes it if there is one: there it costs a velocity of a * left. The -J segment would
    // turn it into an acceleration error J * left, which the rest of the profile (R long) makes
    // J * left * R^2 / 2 of position: from T's rounding alone, 4e-14 m, enough to move the start of
    // a shallow dip by 1e-12 relative (seed 3 problem 3963501). Without a hold the profile is short.
    double& taker = t6 > 0.0 && t6 + left >= 0.0 ? t6 : t2 > 0.0 && t2 + left >= 0.0 ? t2 : t3;
    taker = std::max(taker + left, 0.0);
    if (a1 > 0.0 && a3 < 0.0 && !peak_within_velocity(a1, t2)) return false;
    t = SevenDurations{t1, t2, t3, 0.0, 0.0, t6, t7};
    if (rates != nullptr) {
      const Levels r = rate();
      *rates = SevenDurations{r.a1 * inv_jerk_, r.t2, (r.a1 - r.a3) * inv_jerk_, 0.0, 0.0, r.t6,
                              -r.a3 * inv_jerk_};
    }
    return true;
  };

  // Both held: linear in the two hold times. Tried first: the commonest case (long moves).
  {
    const double rest = T - (2.0 * amax - a0 - 2.0 * amin + af) * inv_jerk_;
    const double base = (2.0 * amax * amax - a0 * a0 + af * af - 2.0 * amin * amin) * 0.5 * inv_jerk_;
    const double t2 = (dv - base - amin * rest) / (amax - amin);
    const auto rate = [&] {
      const double dt2 = -amin / (amax - amin);
      return Levels{0.0, dt2, 0.0, 1.0 - dt2};
    };
    if (accept(amax, t2, amin, rest - t2, rate)) return true;
  }
  // No bound active: T = (2 (a1 - a3) + af - a0) / J and 2 J dv = 2 a1^2 - 2 a3^2 + af^2 - a0^2.
  // s grows with T at J / 2.
  const double s = (j * T + a0 - af) / 2.0;
  if (s <= tol_a) {
    // The reach time itself: a point, any split of the slope will do.
    if (accept(a0, 0.0, a0, 0.0, [&] { return Levels{j / 4.0, 0.0, -j / 4.0, 0.0}; })) return true;
  } else {
    const double c = 2.0 * j * dv - af * af + a0 * a0;
    const double a1 = (c + 2.0 * s * s) / (4.0 * s);
    const auto rate = [&] {
      const double da1 = j / 2.0 * (0.5 - c / (4.0 * s * s));
      return Levels{da1, 0.0, da1 - j / 2.0, 0.0};
    };
    if (accept(a1, 0.0, a1 - s, 0.0, rate)) return true;
  }
  // max_acceleration held: a quadratic in a3.
  {
    const double k = (2.0 * amax - a0 + af) / j;
    const double c = 2.0 * amax * amax - a0 * a0 + af * af + 2.0 * j * amax * (T - k) - 2.0 * j * dv;
    const double disc = amax * amax + c / 2.0;
    if (disc >= -tol_disc) {
      const double root = std::sqrt(std::max(disc, 0.0));
      const double a3 = amax - root;
      const auto rate = [&] {
        const double da3 = root > 0.0 ? -j * amax / (2.0 * root) : 0.0;  // disc grows at J amax
        return Levels{0.0, 1.0 + 2.0 * da3 / j, da3, 0.0};
      };
      if (accept(amax, T - k + 2.0 * a3 / j, a3, 0.0, rate)) return true;
    }
  }
  // min_acceleration held: a quadratic in a1.
  {
    const double d = -a0 * a0 + 2.0 * amin * amin + af * af + 2.0 * amin * (j * T + a0 - af) - 2.0 * j * dv;
    const double disc = amin * amin - d / 2.0;
    if (disc >= -tol_disc) {
      const double root = std::sqrt(std::max(disc, 0.0));
      const double a1 = amin + root;
      const auto rate = [&] {
        const double da1 = root > 0.0 ? -j * amin / (2.0 * root) : 0.0;  // disc grows at -J amin
        return Levels{da1, 0.0, 0.0, 1.0 - 2.0 * da1 / j};
      };
      if (accept(a1, 0.0, amin, T - (2.0 * a1 - a0 - 2.0 * amin + af) / j, rate)) return true;
    }
  }
  return false;
}

template <bool kSlope, bool kArrival>
double FarthestProfile::position_of(const SevenDurations& t, const SevenDurations& rates,
                                    double& slope) const noexcept {
  assert(t[3] == 0.0);
  // Lengthening segment i by dt moves the state at its end by (v, a, jerk) dt, which the rest of
  // the profile (r long, its jerks unchanged) carries to the end as (v + a r + jerk r^2 / 2) dt of
  // position: the slope is the sum of these weighted by the rates.
  double left = 0.0;
  if constexpr (kSlope) {
    for (const double d : t) left += d;
  }
  double sum_slope = 0.0;
  double p = 0.0;
  double v = v0_;
  double a = a0_;
  const double half_jerk_abs = half_jerk_;
  const double sixth_jerk_abs = sixth_jerk_;
  const double jerk = lim_.jerk;
  // Unrolled, each segment's jerk sign a constant (the same arithmetic as with the sign as a factor:
  // a factor of 1 or -1 is exact, a zero jerk only drops terms that are zero): the loop's overhead
  // and its multiplications by the sign were half its cost.
#pragma GCC unroll 7
  for (std::size_t i = 0; i < kFarthestJerkSigns.size(); ++i) {
    if (i == 3) continue;  // the cruise: zero in every profile summed here (see the header)
    const double sign = kFarthestJerkSigns[i];
    const double d = t[i];
    if (sign == 0.0) {
      p += d * (v + d * (a * 0.5));
      v += d * a;
      if constexpr (kSlope) {
        left -= d;
        sum_slope += rates[i] * (v + left * a);
      }
    } else {
      const double half_jerk = sign * half_jerk_abs;
      p += d * (v + d * (a * 0.5 + d * sign * sixth_jerk_abs));
      v += d * (a + d * half_jerk);
      a += d * sign * jerk;
      if constexpr (kSlope) {
        left -= d;
        sum_slope += rates[i] * (v + left * (a + left * half_jerk));
      }
    }
  }
  if constexpr (kSlope) slope = sum_slope;
  if constexpr (kArrival) {
    // AxisProfile's arrival check's tolerances (the spans are the same in either frame).
    if (!(std::abs(v - vf_) <= 1e-9 * (1.0 + lim_.max_velocity - lim_.min_velocity) &&
          std::abs(a - af_) <= 1e-9 * (1.0 + lim_.max_acceleration - lim_.min_acceleration)))
      return std::numeric_limits<double>::quiet_NaN();
  }
  return p;
}

double FarthestProfile::lowest_velocity_of(const SevenDurations& t) const noexcept {
  const double j = lim_.jerk;
  double v = v0_;
  double a = a0_;
  double lowest = v;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double jk = kFarthestJerkSigns[i] * j;
    if (jk > 0.0 && a < 0.0 && a + jk * t[i] > 0.0) lowest = std::min(lowest, v - a * a / (2.0 * jk));
    v += t[i] * (a + t[i] * jk / 2.0);
    a += t[i] * jk;
    lowest = std::min(lowest, v);
  }
  return lowest;
}

double FarthestProfile::duration_to_rest(double target) const noexcept {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (vf_ != 0.0 || af_ != 0.0) return kNaN;
  const double j = lim_.jerk;
  const double amax = lim_.max_acceleration;
  const double floor = -lim_.min_acceleration;
  const double v0 = v0_;
  const double a0 = a0_;
  // The profile peaking at vp: the rise +J to a1 (held at max_acceleration when it would exceed
  // it), -J to (vp, 0); the fall -J to -m (m = sqrt(J vp), or the floor held), +J to rest. The fall
  // is point-symmetric: it covers vp times half its duration vp / m + m / J. Lengthening the rise's
  // hold (or raising its peak) by what raises vp by dvp adds (vp + a1^2 / 2J) / a1 dvp of position
  // (the state after it carried to the end), the fall (vp / m + m / 2J) dvp.
  double a1 = 0.0;
  double m = 0.0;
  double time = 0.0;
  const auto gap = [&](double vp, double& slope) {
    const double x1 = j * (vp - v0) + 0.5 * a0 * a0;
    const bool held = x1 > amax * amax;
    a1 = held ? amax : std::max(std::sqrt(std::max(0.0, x1)), std::max(a0, 0.0));
    const double t1 = (a1 - a0) * inv_jerk_;
    const double t2 = held ? (x1 - amax * amax) * inv_jerk_ / amax : 0.0;
    const double t3 = a1 * inv_jerk_;
    MotionState s{0.0, v0, a0};
    s = integrate(s, j, t1);
    s = integrate(s, 0.0, t2);
    s = integrate(s, -j, t3);
    m = std::min(std::sqrt(j * vp), floor);
    const double fall = vp > 0.0 ? vp / m + m * inv_jerk_ : 0.0;
    time = t1 + t2 + t3 + fall;
    slope = (vp + a1 * a1 * 0.5 * inv_jerk_) / a1 + (vp > 0.0 ? vp / m + m * 0.5 * inv_jerk_ : 0.0);
    return s.position + vp * fall * 0.5 - target;
  };
  // The rise needs a1 >= max(a0, 0): vp from where ramping a0 out ends (and not below zero, where the
  // fall begins) to max_velocity. Short at the lower end (strictly: the positions only grow with
  // the duration, so no earlier duration reaches the target either), not short at the upper one.
  const double lo = std::max(v0 + a0 * std::abs(a0) * 0.5 * inv_jerk_, 0.0);
  const double hi = lim_.max_velocity;
  double slope = 0.0;
  // The duration at the root. It changes with vp at 1 / a1 + 1 / m, much faster than the position
  // where a1 or m is small, so the few ulps by which vp misses the root would show in it (up to
  // 6e-13 relative in random problems): the duration is corrected by the root's offset that the
  // position's residual gives, to first order (what is left is the residual's own rounding, divided
  // by the position's slope). Near a zero peak acceleration or velocity that order is not enough.
  const auto at_root = [&](double vp) {
    const double residual = gap(vp, slope);
    if (!(std::isfinite(residual) && a1 >= 1e-3 * amax && m >= 1e-3 * floor)) return kNaN;
    return time - (1.0 / a1 + 1.0 / m) * residual / slope;
  };
  // Where the rise holds max_acceleration and the fall the floor (two roots in three of the bench's
  // moving starts), both holds grow linearly with vp and the position is quadratic in it:
  // vp^2 (1 / amax + 1 / floor) / 2 + vp (amax + floor) / 2J + c, where c (< 0 where there is a root
  // above zero) holds the rise's first ramp (to v1 at max_acceleration, d1 long) and the target. Its
  // root in closed form, in the form without cancellation, saves the Newton steps (6.5 evaluations,
  // a chain of square roots and divisions); one outside that case leaves them to the search below.
  {
    const double t1 = (amax - a0) * inv_jerk_;
    const double v1 = v0 + (amax * amax - a0 * a0) * 0.5 * inv_jerk_;
    const double d1 = t1 * (v0 + t1 * (a0 * 0.5 + t1 * sixth_jerk_));
    const double qa = 0.5 / amax + 0.5 / floor;
    const double qb = (amax + floor) * 0.5 * inv_jerk_;
    const double qc = d1 - v1 * v1 * 0.5 / amax - amax * amax * amax * inv_jerk_ * inv_jerk_ / 24.0 - target;
    const double vp = -2.0 * qc / (qb + std::sqrt(qb * qb - 4.0 * qa * qc));
    const bool held = vp >= v1 + amax * amax * 0.5 * inv_jerk_;
    const bool capped = vp * j >= floor * floor;
    if (qc < 0.0 && held && capped && vp > lo && vp <= hi) return at_root(vp);
  }
  const double g_lo = gap(lo, slope);
  const double g_hi = gap(hi, slope);
  if (!(g_lo < 0.0 && g_hi >= 0.0)) return kNaN;
  // Started where a position quadratic in vp through both ends would reach the target (the
  // tangent at max_velocity took twice the steps: far from the root each step only halved the way).
  const double start = std::sqrt((g_hi * lo * lo - g_lo * hi * hi) / (g_hi - g_lo));
  return at_root(newton_root(gap, lo, g_lo, hi, g_hi, start));
}

template <bool kArrival>
double FarthestProfile::position_of(const SevenDurations& t) const noexcept {
  double unused = 0.0;
  return position_of<false, kArrival>(t, t, unused);
}

double FarthestProfile::position(double T) const noexcept {
  // Cruising, linear in T (as position(T, t) has it, without the durations).
  if (T >= cruise_from_) return cruise_position_ + lim_.max_velocity * (T - cruise_from_);
  SevenDurations t;
  if (!durations(T, t)) return std::numeric_limits<double>::quiet_NaN();
  return position_of<false>(t);
}

double FarthestProfile::position(double T, SevenDurations& t) const noexcept {
  if (!durations(T, t)) return std::numeric_limits<double>::quiet_NaN();
  return T >= cruise_from_ ? cruise_position_ + lim_.max_velocity * t[3] : position_of<true>(t);
}

double FarthestProfile::position_and_slope(double T, double& slope) const noexcept {
  SevenDurations t{};
  SevenDurations rates{};
  if (!durations(T, t, &rates)) return std::numeric_limits<double>::quiet_NaN();
  if (T >= cruise_from_) {
    slope = lim_.max_velocity;
    return cruise_position_ + lim_.max_velocity * t[3];
  }
  return position_of<true, false>(t, rates, slope);
}

}  // namespace cellctl::planner

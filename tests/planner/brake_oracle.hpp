#pragma once
// The independent optimum of the brake pre-profile, for the planner's tests and benchmark. It
// shares no code with controller/planner (nor its case analysis).
//
// A start may lie beyond the limits: its acceleration beyond a bound, or its velocity beyond one or
// bound to cross one whatever the jerk does next. The brake takes it into the safe set S: the
// states (v, a) with amin <= a <= amax from which the velocity limits can be kept,
// v + max(a, 0)^2 / 2J <= vmax and v - min(a, 0)^2 / 2J >= vmin. The brake is the earliest entry
// into S among the jerk-limited motions that bring an acceleration beyond its bound back at full
// jerk and then keep it within its bounds; the velocity is free on the way (its overshoot is
// unavoidable). After the brake the time-optimal motion within the limits follows.
//
// Found without cases: the states reachable at T form a convex set in (v, a) (linear dynamics,
// convex bounds). For an end acceleration x its velocities are [vlo(x), vhi(x)], the integrals of
// the lowest and the highest acceleration path to x (piecewise linear: integrated exactly between
// their corners). S is convex too, so the reachable set meets S at T exactly when
// min over x of max(L(x) - vhi(x), vlo(x) - U(x)) <= 0 (L, U: S's velocity bounds at x), a convex
// function (golden section). S can be kept once entered, so entry only gets easier with T: the
// earliest T is bisected, and the end state is the touching path's.
// Header-only: the benchmark builds the oracle from its sources too.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "planner/optimum_oracle.hpp"

namespace cellctl::planner::oracle {

// The problem from the end of the brake on, and the brake's duration (0 and `p` itself when the
// start is in S).
struct Braked {
  Problem problem;
  double delay;
};

namespace brake_detail {

inline constexpr double kGolden = 0.6180339887498949;

// S's velocity bounds at acceleration x.
inline double lowest_safe(double x, const Limits& l) {
  const double down = std::min(x, 0.0);
  return l.vmin + down * down / (2.0 * l.jerk);
}
inline double highest_safe(double x, const Limits& l) {
  const double up = std::max(x, 0.0);
  return l.vmax - up * up / (2.0 * l.jerk);
}

struct Motion {
  double p, v, a;
};

// One acceleration path to x at T: the highest (`high`) or the lowest the jerk and the acceleration
// bounds allow. The highest is the least of: rising at full jerk from a0, falling at full jerk onto
// x at T, and amax (or, while an a0 above it comes back at full jerk, that ramp).
struct Path {
  const Problem& p;
  double T;
  double x;
  bool high;

  [[nodiscard]] double at(double t) const {
    const Limits& l = p.limits;
    const double j = l.jerk;
    if (high) return std::min({p.a0 + j * t, x + j * (T - t), std::max(l.amax, p.a0 - j * t)});
    return std::max({p.a0 - j * t, x - j * (T - t), std::min(l.amin, p.a0 + j * t)});
  }

  // The end state from (0, v0, a0): exact, the path being linear between its corners (the
  // crossings of the lines it is made of).
  [[nodiscard]] Motion end() const {
    const Limits& l = p.limits;
    const double j = l.jerk;
    // The lines as (value at 0, slope).
    const std::array<std::array<double, 2>, 6> lines{
        {{p.a0, j}, {p.a0, -j}, {x + j * T, -j}, {x - j * T, j}, {l.amax, 0.0}, {l.amin, 0.0}}};
    std::array<double, 2 + 15> times{};
    std::size_t n = 0;
    times[n++] = 0.0;
    times[n++] = T;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      for (std::size_t k = i + 1; k < lines.size(); ++k) {
        if (lines[i][1] == lines[k][1]) continue;
        const double t = (lines[k][0] - lines[i][0]) / (lines[i][1] - lines[k][1]);
        if (t > 0.0 && t < T) times[n++] = t;
      }
    }
    std::sort(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(n));
    Motion m{0.0, p.v0, at(0.0)};
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double dt = times[i + 1] - times[i];
      if (!(dt > 0.0)) continue;
      const double a1 = at(times[i + 1]);
      const double jerk = (a1 - m.a) / dt;
      m = Motion{m.p + dt * (m.v + dt * (m.a / 2.0 + dt * jerk / 6.0)), m.v + dt * (m.a + dt * jerk / 2.0),
                 a1};
    }
    return m;
  }
};

// How far the states reachable at T with end acceleration x are from S (<= 0: they meet it), and
// which path touches it (the highest when S lies above the reachable velocities).
struct Miss {
  double by;
  bool high;
};
inline Miss miss(const Problem& p, double T, double x) {
  const double above = lowest_safe(x, p.limits) - Path{p, T, x, true}.end().v;
  const double below = Path{p, T, x, false}.end().v - highest_safe(x, p.limits);
  return above >= below ? Miss{above, true} : Miss{below, false};
}

// The end accelerations reachable at T at which S has states (within the bounds, and no more than
// the velocity range can ramp out: |x| <= sqrt(2 J (vmax - vmin))); false when there is none.
inline bool end_accelerations(const Problem& p, double T, double& lo, double& hi) {
  const Limits& l = p.limits;
  const double ramp_out = std::sqrt(2.0 * l.jerk * (l.vmax - l.vmin));
  lo = std::max({l.amin, -ramp_out, p.a0 - l.jerk * T});
  hi = std::min({l.amax, ramp_out, p.a0 + l.jerk * T});
  return lo <= hi;
}

// The end acceleration at T that comes closest to S (golden section on a convex function), and
// how close.
inline double closest(const Problem& p, double T, double& x) {
  double lo = 0.0;
  double hi = 0.0;
  if (!end_accelerations(p, T, lo, hi)) return std::numeric_limits<double>::infinity();
  const auto f = [&](double y) { return miss(p, T, y).by; };
  double a = lo;
  double b = hi;
  double c = b - kGolden * (b - a);
  double d = a + kGolden * (b - a);
  double fc = f(c);
  double fd = f(d);
  for (int i = 0; i < 200 && b - a > 1e-13 * (1.0 + std::abs(a) + std::abs(b)); ++i) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kGolden * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kGolden * (b - a);
      fd = f(d);
    }
  }
  x = 0.5 * (a + b);
  double best = f(x);
  for (const double end : {lo, hi}) {
    if (f(end) < best) {
      best = f(end);
      x = end;
    }
  }
  return best;
}

}  // namespace brake_detail

// Whether (v, a) is in the safe set S of `l`, up to rounding (1e-12 relative): a brake ends on S's
// boundary, and a state an ulp outside it would need a brake of about the square root of that
// distance (1e-8 s for 1e-16), which no rounding should decide.
inline bool in_safe_set(double v, double a, const Limits& l) {
  using brake_detail::highest_safe;
  using brake_detail::lowest_safe;
  const double dv = 1e-12 * (1.0 + l.vmax - l.vmin);
  const double da = 1e-12 * (1.0 + l.amax - l.amin);
  return a <= l.amax + da && a >= l.amin - da && v <= highest_safe(a, l) + dv && v >= lowest_safe(a, l) - dv;
}

// The earliest entry into S and the problem from there on.
inline Braked braked(const Problem& p) {
  using namespace brake_detail;
  const Limits& l = p.limits;
  // In S up to rounding: snapped into it (reach() takes no start outside, by an ulp neither).
  const auto snapped = [&l](Problem q) {
    q.a0 = std::clamp(q.a0, l.amin, l.amax);
    // Where S is a point at this acceleration up to rounding (tight limits: vmax - vmin about
    // a^2 / J), its bounds can cross by an ulp, and std::clamp requires them ordered (a build with
    // _GLIBCXX_ASSERTIONS aborted here): the point is then their middle.
    const double lo = lowest_safe(q.a0, l);
    const double hi = highest_safe(q.a0, l);
    q.v0 = lo <= hi ? std::clamp(q.v0, lo, hi) : 0.5 * (lo + hi);
    return q;
  };
  if (in_safe_set(p.v0, p.a0, l)) return Braked{snapped(p), 0.0};
  double x = 0.0;
  const auto enters = [&](double T) { return closest(p, T, x) <= 0.0; };
  // Too short to bring the acceleration within its bounds; then doubled until S is entered.
  double lo = std::max({0.0, (p.a0 - l.amax) / l.jerk, (l.amin - p.a0) / l.jerk});
  double hi = lo + (l.amax - l.amin) / l.jerk;
  while (!enters(hi)) {
    lo = hi;
    hi *= 2.0;
  }
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (enters(mid) ? hi : lo) = mid;
  }
  closest(p, hi, x);
  const Motion m = Path{p, hi, x, miss(p, hi, x).high}.end();
  Problem after = p;
  after.p0 = p.p0 + m.p;
  after.v0 = m.v;
  after.a0 = x;
  return Braked{snapped(after), hi};  // on S's boundary up to rounding
}

}  // namespace cellctl::planner::oracle

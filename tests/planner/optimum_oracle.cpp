#include "planner/optimum_oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace cellctl::planner::oracle {
namespace {

struct State {
  double p, v, a;
};

struct Piece {
  double jerk, time;
};

State run(State s, const std::array<Piece, 7>& pieces, double* peak_v = nullptr) {
  for (const Piece& pc : pieces) {
    const double t = pc.time;
    if (peak_v != nullptr && s.a > 0.0 && s.a + pc.jerk * t < 0.0) {
      const double tz = -s.a / pc.jerk;  // where the acceleration crosses zero: a velocity peak
      *peak_v = std::max(*peak_v, s.v + s.a * tz + pc.jerk * tz * tz / 2.0);
    }
    s = State{s.p + s.v * t + s.a * t * t / 2.0 + pc.jerk * t * t * t / 6.0,
              s.v + s.a * t + pc.jerk * t * t / 2.0, s.a + pc.jerk * t};
    if (peak_v != nullptr) *peak_v = std::max(*peak_v, s.v);
  }
  return s;
}

// Finds x in [lo, hi] with f(x) = 0 for an increasing f, by bisection.
template <typename F>
double solve_increasing(const F& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The jerk sequence of effort u (0 .. max) for duration T: +J for the first part of u, then the
// acceleration held at amax for the rest of u, then -J down to a level a3 (held at amin if it would
// go below) and +J to af, the levels chosen so that the whole takes exactly T. More u, more speed.
bool sequence(const Problem& pr, double T, double u, std::array<Piece, 7>& out) {
  const Limits& l = pr.limits;
  const double j = l.jerk;
  const double ramp = l.amax - pr.a0;
  const double a1 = u <= ramp ? pr.a0 + u : l.amax;
  const double hold1 = u <= ramp ? 0.0 : (u - ramp) / j;
  const double rest = T - (a1 - pr.a0) / j - hold1;
  if (rest < 0.0) return false;
  double a3 = (a1 + pr.af - j * rest) / 2.0;
  double hold3 = 0.0;
  if (a3 < l.amin) {
    a3 = l.amin;
    hold3 = rest - (a1 + pr.af - 2.0 * l.amin) / j;
  }
  if (a3 > pr.af || a3 > a1) return false;
  out = {Piece{j, (a1 - pr.a0) / j},
         Piece{0.0, hold1},
         Piece{-j, (a1 - a3) / j},
         Piece{0.0, 0.0},
         Piece{0.0, 0.0},
         Piece{0.0, hold3},
         Piece{j, (pr.af - a3) / j}};
  return true;
}

// The farthest end position at duration T with the target's end velocity and acceleration; NaN
// when that end state cannot be reached at T.
double farthest(const Problem& pr, double T) {
  const Limits& l = pr.limits;
  const double j = l.jerk;
  const State s0{0.0, pr.v0, pr.a0};
  // More effort, more end velocity; too much effort leaves no time for the end (counted as "too
  // fast"), so the end velocity is increasing over the whole range and one bisection finds it.
  const double u_top = (l.amax - pr.a0) + j * T;
  std::array<Piece, 7> seq{};
  const auto end_v = [&](double u) { return sequence(pr, T, u, seq) ? run(s0, seq).v - pr.vf : 1e300; };
  if (end_v(0.0) > 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double u = end_v(0.0) == 0.0 ? 0.0 : solve_increasing(end_v, 0.0, u_top);
  if (!sequence(pr, T, u, seq) ||
      std::abs(run(s0, seq).v - pr.vf) > 1e-9 * (1.0 + std::abs(pr.vf) + l.vmax)) {
    return std::numeric_limits<double>::quiet_NaN();  // even the most effort cannot reach vf at T
  }
  double peak = -1e300;
  const State end = run(s0, seq, &peak);
  if (peak <= l.vmax * (1.0 + 1e-12)) return end.p;
  // Too fast on the way: rise to vmax as fast as possible, cruise, fall to the end as late as possible.
  const auto rise = [&](double w) {  // +J to level w (held at amax), -J to zero
    const double lvl = std::min(w, l.amax);
    const double hold = std::max(0.0, w - l.amax) / j;
    return std::array<Piece, 7>{Piece{j, (lvl - pr.a0) / j},
                                Piece{0.0, hold},
                                Piece{-j, lvl / j},
                                Piece{0.0, 0.0},
                                Piece{0.0, 0.0},
                                Piece{0.0, 0.0},
                                Piece{0.0, 0.0}};
  };
  const double w = solve_increasing([&](double x) { return run(s0, rise(x)).v - l.vmax; },
                                    std::max(pr.a0, 0.0), l.amax + j * T);
  const auto fall = [&](double x) {  // -J to level -x (held at amin beyond it), +J to af
    const double lvl = std::max(-x, l.amin);
    const double hold = std::max(0.0, x + l.amin) / j;
    return std::array<Piece, 7>{Piece{-j, -lvl / j}, Piece{0.0, hold}, Piece{j, (pr.af - lvl) / j},
                                Piece{0.0, 0.0},     Piece{0.0, 0.0},  Piece{0.0, 0.0},
                                Piece{0.0, 0.0}};
  };
  const State top{0.0, l.vmax, 0.0};
  const double x = solve_increasing([&](double y) { return pr.vf - run(top, fall(y)).v; },
                                    std::max(-pr.af, 0.0), -l.amin + j * T);
  const auto up = rise(w);
  const auto down = fall(x);
  double t_up = 0.0;
  double t_down = 0.0;
  for (const Piece& pc : up) t_up += pc.time;
  for (const Piece& pc : down) t_down += pc.time;
  const double cruise = T - t_up - t_down;
  if (cruise < -1e-12 * T) return end.p;  // cannot happen for a farthest profile; keep the first answer
  const State after_up = run(s0, up);
  const State after_cruise{after_up.p + l.vmax * std::max(cruise, 0.0), l.vmax, 0.0};
  return run(after_cruise, down).p;
}

Problem mirrored(const Problem& p) {
  return Problem{-p.p0,
                 -p.v0,
                 -p.a0,
                 -p.pf,
                 -p.vf,
                 -p.af,
                 Limits{-p.limits.vmin, -p.limits.vmax, -p.limits.amin, -p.limits.amax, p.limits.jerk}};
}

}  // namespace

bool feasible(const Problem& p, double T) {
  const double far = farthest(p, T);
  const double near = -farthest(mirrored(p), T);
  const double target = p.pf - p.p0;
  return std::isfinite(far) && std::isfinite(near) && near <= target && target <= far;
}

namespace {

template <typename Feasible>
double first_feasible(const Feasible& ok, double upper) {
  constexpr int kScan = 24;
  double prev = 0.0;
  if (ok(0.0)) return 0.0;
  for (int k = 1; k <= kScan; ++k) {
    const double T = upper * k / kScan;
    if (!ok(T)) {
      prev = T;
      continue;
    }
    double lo = prev;
    double hi = T;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (ok(mid) ? hi : lo) = mid;
    }
    return hi;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

bool confirms_min_common_duration(const std::vector<Problem>& problems, double T, double relative) {
  const auto all = [&](double t) {
    return std::all_of(problems.begin(), problems.end(), [t](const Problem& p) { return feasible(p, t); });
  };
  if (T == 0.0) return all(0.0);
  if (!all(T * (1.0 + relative) + 1e-15)) return false;
  const double below = T * (1.0 - relative);
  constexpr int kScan = 12;
  for (int k = 0; k <= kScan; ++k) {
    if (all(below * k / kScan)) return false;
  }
  return true;
}

bool confirms_min_duration(const Problem& p, double T, double relative) {
  return confirms_min_common_duration({p}, T, relative);
}

double min_duration(const Problem& p, double upper) {
  return first_feasible([&](double T) { return feasible(p, T); }, upper);
}

double min_common_duration(const std::vector<Problem>& problems, double upper) {
  return first_feasible(
      [&](double T) {
        return std::all_of(problems.begin(), problems.end(),
                           [T](const Problem& p) { return feasible(p, T); });
      },
      upper);
}

}  // namespace cellctl::planner::oracle

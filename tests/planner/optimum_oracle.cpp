#include "planner/optimum_oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "planner/brake_oracle.hpp"

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
  // Where f ends in a jump to "no such motion" (1e300) rather than crossing zero — the end velocity
  // just after the reach time — the root is the last x that has a motion: lo, not the midpoint.
  const double mid = 0.5 * (lo + hi);
  return f(mid) >= 1e300 ? lo : mid;
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
  // The least effort already too fast: no motion — but for rounding at the reach time, where the
  // least effort is the only motion.
  const double least = end_v(0.0);
  if (least > 1e-12 * (1.0 + std::abs(pr.vf) + l.vmax)) return std::numeric_limits<double>::quiet_NaN();
  const double u = least >= 0.0 ? 0.0 : solve_increasing(end_v, 0.0, u_top);
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

bool Reach::defined() const {
  return std::isfinite(near) && std::isfinite(far);
}

Reach reach(const Problem& p, double T) {
  return Reach{-farthest(mirrored(p), T), farthest(p, T)};
}

namespace {

bool holds(const Reach& r, double target) {
  return r.defined() && r.near <= target && target <= r.far;
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// What the insertion argument (see the header) knows about one problem, independent of T: bounds
// on the velocity w of a cruise that can be inserted into every motion, and the durations that a
// motion without a zero-acceleration point could have (where it knows nothing).
struct Insertion {
  double w_lo = 0.0;           // some insertion point of every motion has w >= w_lo ...
  double w_hi = 0.0;           // ... and one has w <= w_hi
  double mono_lo = kInfinity;  // [mono_lo, mono_hi]: empty unless a0 and af share a sign
  double mono_hi = -kInfinity;
};

Insertion insertion(const Problem& p) {
  Insertion in;
  // Every velocity on the way is within the limits. Better: at the first zero of the acceleration
  // the velocity has risen from v0 if a0 > 0 (w >= v0), fallen if a0 < 0 (w <= v0); at the last it
  // rises on to vf if af > 0 (w <= vf), falls if af < 0 (w >= vf); a0 = 0 or af = 0 is a zero with
  // w = v0 or vf. The proof at hand picks the point with the better bound.
  in.w_lo = p.limits.vmin;
  in.w_hi = p.limits.vmax;
  if (p.a0 >= 0.0) in.w_lo = std::max(in.w_lo, p.v0);
  if (p.a0 <= 0.0) in.w_hi = std::min(in.w_hi, p.v0);
  if (p.af <= 0.0) in.w_lo = std::max(in.w_lo, p.vf);
  if (p.af >= 0.0) in.w_hi = std::min(in.w_hi, p.vf);
  if (p.a0 == 0.0 || p.af == 0.0) return in;
  if ((p.a0 > 0.0) == (p.af > 0.0)) {
    // The acceleration may keep its sign throughout (say positive: else mirrored). The velocity then
    // rises from v0 at least as a >= max(0, a0 - J t) lets it and ends at vf no faster than
    // a >= max(0, af - J (T - t)) lets it; integrated, and bounded by the tangents of those convex
    // curves: (v0 + c0) T - k0 <= D <= (vf - cf) T + kf, c = a^2 / 2J, k = a^3 / 6J^2. Those T form
    // an interval.
    const Problem q = p.a0 > 0.0 ? p : mirrored(p);
    const double j = q.limits.jerk;
    const double D = q.pf - q.p0;
    const double low_slope = q.v0 + q.a0 * q.a0 / (2.0 * j);  // low_slope T - k0 <= D
    const double k0 = q.a0 * q.a0 * q.a0 / (6.0 * j * j);
    const double high_slope = q.vf - q.af * q.af / (2.0 * j);  // high_slope T + kf >= D
    const double kf = q.af * q.af * q.af / (6.0 * j * j);
    double lo = 0.0;
    double hi = kInfinity;
    // s T <= c, T >= 0
    const auto at_most = [&](double slope, double c) {
      if (slope > 0.0) hi = std::min(hi, c / slope);
      if (slope < 0.0) lo = std::max(lo, c / slope);
      if (slope == 0.0 && c < 0.0) hi = -kInfinity;
    };
    at_most(low_slope, D + k0);
    at_most(-high_slope, kf - D);
    if (lo <= hi) {
      in.mono_lo = lo;
      in.mono_hi = hi;
    }
  }
  return in;
}

// The end velocities reachable at T with the end acceleration af under the acceleration and jerk
// limits alone (a superset of those within the velocity limits too): [lo, hi], the least and the
// most effort (the acceleration along its lower or upper envelope). False when af itself cannot be
// reached at T.
bool end_velocities(const Problem& p, double T, double& lo, double& hi) {
  std::array<Piece, 7> seq{};
  if (!sequence(p, T, 0.0, seq)) return false;
  lo = run(State{0.0, p.v0, p.a0}, seq).v;
  const Problem m = mirrored(p);
  if (!sequence(m, T, 0.0, seq)) return false;
  hi = -run(State{0.0, m.v0, m.a0}, seq).v;
  return true;
}

// How far below b, where the end state (vf, af) is out of reach, it is proven out of reach for every
// motion: holding the acceleration for b - t at its highest point a* >= max(a0, af) turns a motion
// of duration t into one of duration b ending a* (b - t) faster, so hi(b) < vf rules out every t
// with a* (b - t) > hi(b) - vf (all t < b when a* can be >= 0); likewise lo(b) > vf with
// min(a0, af). No insertion point needed: this covers the unresolved interval too.
double unreachable_step(const Problem& p, double b) {
  double lo = 0.0;
  double hi = 0.0;
  if (!end_velocities(p, b, lo, hi)) return kInfinity;  // |af - a0| > J b > J t
  const double eps = 1e-12 * (1.0 + std::abs(p.vf) + std::max(p.limits.vmax, -p.limits.vmin));
  const double top = std::max(p.a0, p.af);
  const double bottom = std::min(p.a0, p.af);
  if (hi < p.vf) return top >= 0.0 ? kInfinity : std::max(p.vf - hi, eps) / -top;
  if (lo > p.vf) return bottom <= 0.0 ? kInfinity : std::max(lo - p.vf, eps) / bottom;
  return 0.0;
}

// How far below b (infeasible for p, reach r there) every duration is proven infeasible too:
// [b - step, b], up to the position tolerance eps. 0 when nothing is proven (b lies in the
// unresolved interval and the end state is within reach).
double proven_step(const Problem& p, const Insertion& in, const Reach& r, double b, double eps) {
  const double target = p.pf - p.p0;
  double step = 0.0;   // a side the bisection could not settle (NaN) proves nothing on its own
  double every = 0.0;  // what holds for motions without an insertion point too
  if (std::isnan(r.far) && std::isnan(r.near)) {
    // The end state out of reach at b (confirmed by the end velocities, in closed form): a motion at
    // t < b with an insertion point would reach it at b.
    every = unreachable_step(p, b);
    step = every > 0.0 ? kInfinity : 0.0;
  } else if (r.far < target) {
    step = in.w_lo >= 0.0 ? kInfinity : std::max(target - r.far, eps) / -in.w_lo;
  } else if (r.near > target) {
    step = in.w_hi <= 0.0 ? kInfinity : std::max(r.near - target, eps) / in.w_hi;
  }
  if (in.mono_lo < b) step = b <= in.mono_hi ? 0.0 : std::min(step, b - in.mono_hi);
  return std::max(step, every);
}

// The position tolerance of a proof at b: above the oracle's rounding, far below anything the
// planner's 1e-9 relative duration could mean.
double tolerance(const Problem& p, double b) {
  return 1e-12 * (1.0 + std::abs(p.pf - p.p0) + std::max(p.limits.vmax, -p.limits.vmin) * b);
}

enum class Below { none, found, undecided };

// Whether any duration in [0, x] is feasible for every problem: the scan down from x, each step
// as long as the proof at its top allows; where none does (inside an unresolved interval), a grid
// step of 1/1024 of the unresolved interval below x (the narrowest of the problems'). A problem
// whose start needs a brake is proven on its own clock, which starts at the brake's end: durations
// before it are infeasible for it.
Below scan_below(const std::vector<Braked>& problems, double x) {
  constexpr double kGrid = 1024.0;
  constexpr long kMaxSteps = 200000;
  std::vector<Insertion> ins;
  ins.reserve(problems.size());
  double grid = x / kGrid;
  for (const Braked& q : problems) {
    ins.push_back(insertion(q.problem));
    const double unresolved = std::min(ins.back().mono_hi, x - q.delay) - ins.back().mono_lo;
    if (unresolved > 0.0) grid = std::min(grid, unresolved / kGrid);
  }
  std::vector<char> near_first(problems.size(), 0);
  double b = x;
  for (long n = 0; n < kMaxSteps; ++n) {
    double step = 0.0;
    bool all = true;
    for (std::size_t i = 0; i < problems.size(); ++i) {
      const Problem& p = problems[i].problem;
      const double own = b - problems[i].delay;  // b on the problem's clock
      if (own < 0.0) return Below::none;         // [0, b] lies within its brake
      const double target = p.pf - p.p0;
      // One side short of the target decides alone: the side that did last time is tried first.
      Reach r{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
      if (near_first[i]) r.near = -farthest(mirrored(p), own);
      if (!(r.near > target)) r.far = farthest(p, own);
      if (!(r.far < target) && !near_first[i]) r.near = -farthest(mirrored(p), own);
      near_first[i] = r.near > target;
      if (holds(r, target)) continue;
      all = false;
      const double proven = proven_step(p, ins[i], r, own, tolerance(p, own));
      if (proven >= own) return Below::none;  // this problem alone rules out [0, b]
      step = std::max(step, proven);
    }
    if (all) return Below::found;
    if (b <= 0.0) return Below::none;
    b = step > 0.0 ? b - step : std::max(b - grid, 0.0);
  }
  return Below::undecided;
}

bool feasible_all(const std::vector<Braked>& problems, double T) {
  return std::all_of(problems.begin(), problems.end(), [T](const Braked& q) {
    return T >= q.delay && holds(reach(q.problem, T - q.delay), q.problem.pf - q.problem.p0);
  });
}

std::vector<Braked> all_braked(const std::vector<Problem>& problems) {
  std::vector<Braked> out;
  out.reserve(problems.size());
  for (const Problem& p : problems) out.push_back(braked(p));
  return out;
}

}  // namespace

bool feasible(const Problem& p, double T) {
  return feasible_all({braked(p)}, T);
}

bool confirms_min_common_duration(const std::vector<Problem>& problems, double T, double relative) {
  const std::vector<Braked> all = all_braked(problems);
  if (T == 0.0) return feasible_all(all, 0.0);
  if (!feasible_all(all, T * (1.0 + relative) + 1e-15)) return false;
  const Below below = scan_below(all, T * (1.0 - relative));
  if (below == Below::undecided) {
    std::fprintf(stderr, "optimum_oracle: the scan below %.17g s gave up (the target grazes a reach)\n", T);
  }
  return below == Below::none;
}

bool confirms_min_duration(const Problem& p, double T, double relative) {
  return confirms_min_common_duration({p}, T, relative);
}

double min_common_duration(const std::vector<Problem>& problems, double upper) {
  const std::vector<Braked> all = all_braked(problems);
  if (feasible_all(all, 0.0)) return 0.0;
  if (scan_below(all, upper) == Below::none) return kInfinity;
  // Bisection on "some duration in [0, x] is feasible", which holds from the optimum on.
  double lo = 0.0;
  double hi = upper;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (scan_below(all, mid) == Below::none ? lo : hi) = mid;
  }
  return hi;
}

double min_duration(const Problem& p, double upper) {
  return min_common_duration({p}, upper);
}

}  // namespace cellctl::planner::oracle

#pragma once
// The one-dimensional searches over durations the axis planner needs (private to the planner).

#include <cmath>
#include <limits>

namespace cellctl::planner {

// g(lo) and g(hi) lie on different sides of "g >= 0"; narrows the bracket to the last bit and
// returns its end on the side where g >= 0 (so the returned duration is feasible for this side).
// Regula falsi with the Illinois fix (superlinear on these smooth pieces), falling back to a
// bisection step whenever the bracket stops halving.
template <typename G>
double find_root(const G& g, double lo, double hi, bool lo_reaches) noexcept {
  double g_lo = g(lo);
  double g_hi = g(hi);
  int side = 0;  // which end stayed last time (for the Illinois halving)
  double width = hi - lo;
  for (int i = 0; i < 200; ++i) {
    double mid = lo - g_lo * (hi - lo) / (g_hi - g_lo);
    if (!(mid > lo && mid < hi) || i % 4 == 3) {
      if (hi - lo > 0.5 * width) mid = lo + (hi - lo) / 2.0;
      width = hi - lo;
    }
    if (!(mid > lo && mid < hi)) mid = lo + (hi - lo) / 2.0;
    if (mid <= lo || mid >= hi) break;
    const double g_mid = g(mid);
    if ((g_mid >= 0.0) == lo_reaches) {
      lo = mid;
      g_lo = g_mid;
      if (side == -1) g_hi /= 2.0;
      side = -1;
    } else {
      hi = mid;
      g_hi = g_mid;
      if (side == 1) g_lo /= 2.0;
      side = 1;
    }
    if (g_mid == 0.0) return mid;
  }
  return lo_reaches ? lo : hi;
}

// The minimum of g on [lo, hi] (unimodal there) by golden-section search: its argument.
template <typename G>
double golden_minimum(const G& g, double lo, double hi, double below) noexcept {
  constexpr double kInvPhi = 0.6180339887498949;
  double x1 = hi - kInvPhi * (hi - lo);
  double x2 = lo + kInvPhi * (hi - lo);
  double g1 = g(x1);
  double g2 = g(x2);
  // To the tenth digit of the range is enough to tell whether the minimum is below zero (the
  // function is flat there); a value below `below` ends the search at once.
  const double width = 1e-10 * (hi - lo);
  for (int i = 0; i < 200 && hi - lo > width && g1 >= below && g2 >= below; ++i) {
    if (g1 <= g2) {
      hi = x2;
      x2 = x1;
      g2 = g1;
      x1 = hi - kInvPhi * (hi - lo);
      g1 = g(x1);
    } else {
      lo = x1;
      x1 = x2;
      g1 = g2;
      x2 = lo + kInvPhi * (hi - lo);
      g2 = g(x2);
    }
  }
  return g1 <= g2 ? x1 : x2;
}

// g rises through zero on [lo, hi]: g(lo) = g_lo < 0 <= g(hi) = g_hi. gs(T, slope) returns g(T) and
// sets its slope. Returns a duration where g >= 0 no more than a few ulps (g's own rounding) above
// the root. Newton from `x` (the secant's root if x is not inside), kept inside the bracket: a
// bisection step when a step would leave it or stops halving it, as where the slope jumps between
// cases of active bounds. Done when a step from the feasible side is below rounding; from the other
// side it steps a little past the root instead.
template <typename GS>
double newton_root(const GS& gs, double lo, double g_lo, double hi, double g_hi, double x) noexcept {
  const auto secant = [&] { return lo - g_lo * (hi - lo) / (g_hi - g_lo); };
  if (!(x > lo && x < hi)) x = secant();
  if (!(x > lo && x < hi)) x = lo + (hi - lo) / 2.0;
  double step_before = hi - lo;
  double nudge = 0.0;
  for (int i = 0; i < 100; ++i) {
    double slope = 0.0;
    const double g = gs(x, slope);
    if (g >= 0.0) {
      hi = x;
      g_hi = g;
    } else {
      lo = x;  // also a NaN: no profile there, the caller has noted it
      g_lo = g;
    }
    const double ulp = hi * std::numeric_limits<double>::epsilon();  // one or two ulps of hi (> 0)
    const double step = g / slope;
    const bool converged = std::abs(step) <= 8.0 * ulp;
    if (hi - lo <= 8.0 * ulp || (converged && g >= 0.0)) break;
    // Converging quadratically from the feasible side, the step after this one would be about
    // step^3 / step_before^2: below rounding, this step lands on the root (a few ulps added for g's
    // own rounding) and the evaluation that would only confirm it is saved.
    if (g >= 0.0 && !converged && std::abs(step) <= 1e-6 * hi && std::abs(step) < step_before / 2.0) {
      const double next_step = std::abs(step) * (step / step_before) * (step / step_before);
      if (next_step <= ulp) return x - step + 4.0 * ulp;
    }
    double next = x - step;
    if (converged) {
      // Short by rounding: step past the root, further each time rounding says no.
      nudge = nudge == 0.0 ? 2.0 * ulp : 2.0 * nudge;
      next += nudge;
    } else if (!(next > lo && next < hi)) {
      next = secant();  // past an end, the root is next to it: the bracket's secant lands by it
    }
    if (!(next > lo && next < hi) || (!converged && std::abs(step) > step_before / 2.0)) {
      next = lo + (hi - lo) / 2.0;
      step_before = hi - lo;
    } else if (!converged) {
      step_before = std::abs(step);
    }
    x = next;
  }
  return hi;
}

}  // namespace cellctl::planner

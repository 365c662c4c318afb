#include "journal/plot_scale.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cellctl::journal {

Scale nice_scale(double lo, double hi, int max_ticks) {
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-9) lo -= 0.5, hi += 0.5;
  const double rough = (hi - lo) / std::max(1, max_ticks - 1);
  const double power = std::pow(10.0, std::floor(std::log10(rough)));
  double step = 10.0 * power;
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= rough) {
      step = m * power;
      break;
    }
  Scale s;
  s.step = step;
  s.lo = std::floor(lo / step + 1e-9) * step;
  s.hi = std::ceil(hi / step - 1e-9) * step;
  for (int i = 0; s.lo + i * step <= s.hi + step * 1e-6; ++i) {
    const double v = s.lo + i * step;
    s.ticks.push_back(std::abs(v) < step * 1e-6 ? 0.0 : v);  // no "-0"
  }
  return s;
}

std::string Scale::label(double v) const {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  return fmt::format("{:.{}f}", v, decimals);
}

}  // namespace cellctl::journal

#include "plant_link/tag_resolution.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::plant_link {

int position_decimals(const config::AxisConfig& axis) noexcept {
  if (!(axis.edges_per_mm > 0.0)) return 3;
  // The edge is 1/edges_per_mm mm: 10^-d must be no coarser than it (1e-9 for 10^k edges/mm exactly).
  return std::clamp(static_cast<int>(std::ceil(std::log10(axis.edges_per_mm) - 1e-9)), 0, 6);
}

double to_decimals(double v, int decimals) noexcept {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale + 0.0;  // + 0.0: -0 becomes 0
}

}  // namespace cellctl::plant_link

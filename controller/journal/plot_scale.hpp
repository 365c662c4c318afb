#pragma once
// Axis scales a person reads at a glance: ticks on round numbers (1, 2 or 5 × 10^k), the range
// widened to the ticks around the data, labels with just the decimals the step needs.

#include <string>
#include <vector>

namespace cellctl::journal {

struct Scale {
  double lo = 0.0;
  double hi = 1.0;
  double step = 0.2;
  std::vector<double> ticks;                        // lo, lo + step, … hi
  [[nodiscard]] std::string label(double v) const;  // "-6", "2.5", "0.05"
};

// At most about `max_ticks` ticks covering [lo, hi]; an empty or flat range gets a unit span.
[[nodiscard]] Scale nice_scale(double lo, double hi, int max_ticks = 8);

}  // namespace cellctl::journal

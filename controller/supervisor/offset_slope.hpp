#pragma once
// How the SCU's position reading drifts from the encoder's along the travel: the slope of a
// least-squares line through (encoder position, SCU − encoder) samples taken while an axis moves
// steadily. A scale error in the SCU's position sensor is such a slope (0.002 for a sensor that reads
// 0.2 % long); the move executor uses it to correct the SCU's target while the axis still moves.
//
// Only the slope is meant to be used. The SCU's positions reach us some milliseconds after it
// sampled them (the RC reply on the line), which at a steady speed v shifts every sample's offset by
// the same −v·delay: the intercept takes that up and the slope stays true. The offset at rest, where
// no delay matters, comes from elsewhere.

#include <cmath>
#include <cstddef>

namespace cellctl::supervisor {

class OffsetSlope {
 public:
  void reset() noexcept { *this = OffsetSlope{}; }

  void add(double position_mm, double offset_mm) noexcept {
    // Welford's running means and co-moments: no cancellation of large sums.
    ++n_;
    const double dx = position_mm - mean_x_;
    mean_x_ += dx / static_cast<double>(n_);
    const double dy = offset_mm - mean_y_;
    mean_y_ += dy / static_cast<double>(n_);
    sxx_ += dx * (position_mm - mean_x_);
    sxy_ += dx * (offset_mm - mean_y_);
    syy_ += dy * (offset_mm - mean_y_);
    if (n_ == 1) lowest_ = highest_ = position_mm;
    lowest_ = std::fmin(lowest_, position_mm);
    highest_ = std::fmax(highest_, position_mm);
  }

  [[nodiscard]] std::size_t count() const noexcept { return n_; }
  // How much of the travel the samples cover [mm].
  [[nodiscard]] double span_mm() const noexcept { return n_ == 0 ? 0.0 : highest_ - lowest_; }
  // d(SCU − encoder) / d(encoder position); 0 until two distinct positions are in.
  [[nodiscard]] double slope() const noexcept { return sxx_ > 0.0 ? sxy_ / sxx_ : 0.0; }
  // The slope's standard error from the scatter about the line (the SCU's 0.1 mm edges, noise);
  // infinite until there are three samples.
  [[nodiscard]] double slope_error() const noexcept {
    if (n_ < 3 || !(sxx_ > 0.0)) return INFINITY;
    const double residual = std::fmax(syy_ - sxy_ * sxy_ / sxx_, 0.0);
    return std::sqrt(residual / static_cast<double>(n_ - 2) / sxx_);
  }

 private:
  std::size_t n_ = 0;
  double mean_x_ = 0.0;
  double mean_y_ = 0.0;
  double sxx_ = 0.0;
  double sxy_ = 0.0;
  double syy_ = 0.0;
  double lowest_ = 0.0;
  double highest_ = 0.0;
};

}  // namespace cellctl::supervisor

#pragma once
// How the SCU's position reading drifts from the encoder's along the travel: the slope s of
//   SCU − encoder = c + s · position − delay · speed,
// fitted by least squares to samples taken while an axis moves. A scale error in the SCU's position
// sensor is such a slope (0.002 for a sensor that reads 0.2 % long); the move executor uses it to
// correct the SCU's target while the axis still moves.
//
// The SCU's positions reach us some milliseconds after it sampled them (the RC reply on the line),
// which shifts each sample's offset by −speed·delay: at one steady speed the intercept takes that up,
// and where the speed changes during the move (the executor's speed modulation) the speed term
// learns the delay, so neither bends the slope. Only the slope is meant to be used: the offset at
// rest, where no delay matters, comes from elsewhere.

#include <cmath>
#include <cstddef>

namespace cellctl::motion {

class OffsetSlope {
 public:
  void reset() noexcept { *this = OffsetSlope{}; }

  void add(double position_mm, double speed_mm_s, double offset_mm) noexcept {
    // Running means and co-moments (Welford): no cancellation of large sums.
    ++n_;
    const double k = static_cast<double>(n_);
    const double dx = position_mm - mean_x_;
    const double dv = speed_mm_s - mean_v_;
    const double dy = offset_mm - mean_y_;
    mean_x_ += dx / k;
    mean_v_ += dv / k;
    mean_y_ += dy / k;
    const double ex = position_mm - mean_x_;
    const double ev = speed_mm_s - mean_v_;
    const double ey = offset_mm - mean_y_;
    xx_ += dx * ex;
    xv_ += dx * ev;
    vv_ += dv * ev;
    xy_ += dx * ey;
    vy_ += dv * ey;
    yy_ += dy * ey;
    if (n_ == 1) lowest_ = highest_ = position_mm;
    lowest_ = std::fmin(lowest_, position_mm);
    highest_ = std::fmax(highest_, position_mm);
  }

  [[nodiscard]] std::size_t count() const noexcept { return n_; }
  // How much of the travel the samples cover [mm].
  [[nodiscard]] double span_mm() const noexcept { return n_ == 0 ? 0.0 : highest_ - lowest_; }
  // d(SCU − encoder) / d(position); 0 until there is a line.
  [[nodiscard]] double slope() const noexcept { return fit().slope; }
  // The slope's standard error from the scatter about the fit (the SCU's 0.1 mm edges, noise), and
  // large where position and speed moved together so that the two cannot be told apart; infinite
  // until there are more samples than unknowns.
  [[nodiscard]] double slope_error() const noexcept { return fit().error; }

 private:
  struct Fit {
    double slope = 0.0;
    double error = INFINITY;
  };

  [[nodiscard]] Fit fit() const noexcept {
    if (!(xx_ > 0.0)) return {};
    // A speed spread below this leaves the delay's share below a micrometre (for delays up to 50 ms).
    constexpr double kOneSpeed_mm_s = 0.02;
    if (vv_ > kOneSpeed_mm_s * kOneSpeed_mm_s * static_cast<double>(n_)) {
      // Position and speed both vary: the slope with the delay's share taken out. Where they varied
      // together, the two cannot be told apart.
      const double det = xx_ * vv_ - xv_ * xv_;
      if (!(det > 1e-9 * xx_ * vv_)) return {};
      const double s = (xy_ * vv_ - vy_ * xv_) / det;
      const double d = (vy_ * xx_ - xy_ * xv_) / det;
      if (n_ < 4) return {s, INFINITY};
      const double residual = std::fmax(yy_ - s * xy_ - d * vy_, 0.0);
      return {s, std::sqrt(residual / static_cast<double>(n_ - 3) * vv_ / det)};
    }
    // One speed throughout: the delay is part of the intercept (and no speed term is fitted).
    const double s = xy_ / xx_;
    if (n_ < 3) return {s, INFINITY};
    const double residual = std::fmax(yy_ - s * xy_, 0.0);
    return {s, std::sqrt(residual / static_cast<double>(n_ - 2) / xx_)};
  }

  std::size_t n_ = 0;
  double mean_x_ = 0.0;
  double mean_v_ = 0.0;
  double mean_y_ = 0.0;
  double xx_ = 0.0;
  double xv_ = 0.0;
  double vv_ = 0.0;
  double xy_ = 0.0;
  double vy_ = 0.0;
  double yy_ = 0.0;
  double lowest_ = 0.0;
  double highest_ = 0.0;
};

}  // namespace cellctl::motion

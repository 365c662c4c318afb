#pragma once
// The encoder's shaft, coupled to one linear axis (rack, belt or measuring wheel): turns per mm of
// true travel, with an optional slip (the shaft turns a little less than the travel implies) and a
// mounting offset. The encoder emulator turns revolutions into counts by its own resolution.

#include <functional>

namespace cellctl::plant {

struct ShaftParams {
  double mm_per_revolution = 4.0;
  double slip = 0.0;                // fraction: revolutions × (1 − slip)
  double offset_revolutions = 0.0;  // where the shaft stood when the axis was at 0 mm
};

class Shaft {
 public:
  // axis_position_mm: the true position of the coupled axis (e.g. Actuator::true_position_mm()).
  Shaft(const ShaftParams& params, std::function<double()> axis_position_mm)
      : params_(params), axis_position_mm_(std::move(axis_position_mm)) {}

  [[nodiscard]] double revolutions() const {
    return params_.offset_revolutions +
           axis_position_mm_() * (1.0 - params_.slip) / params_.mm_per_revolution;
  }
  void set_slip(double slip) noexcept { params_.slip = slip; }
  [[nodiscard]] const ShaftParams& params() const noexcept { return params_; }

 private:
  ShaftParams params_;
  std::function<double()> axis_position_mm_;
};

}  // namespace cellctl::plant

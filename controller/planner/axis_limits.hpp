#pragma once
// The kinematic limits of one axis. Velocity and acceleration have separate bounds for each
// direction (min_* < 0 < max_*), so a slower retract or a gentler deceleration can be asked for;
// the jerk bound is symmetric.

namespace cellctl::planner {

struct AxisLimits {
  double max_velocity = 0.0;
  double min_velocity = 0.0;  // < 0
  double max_acceleration = 0.0;
  double min_acceleration = 0.0;  // < 0
  double jerk = 0.0;

  // Symmetric limits ±velocity, ±acceleration.
  [[nodiscard]] static constexpr AxisLimits symmetric(double velocity, double acceleration,
                                                      double jerk) noexcept {
    return AxisLimits{velocity, -velocity, acceleration, -acceleration, jerk};
  }
  // The limits seen in the mirrored frame (position, velocity, acceleration negated).
  [[nodiscard]] constexpr AxisLimits mirrored() const noexcept {
    return AxisLimits{-min_velocity, -max_velocity, -min_acceleration, -max_acceleration, jerk};
  }
};

}  // namespace cellctl::planner

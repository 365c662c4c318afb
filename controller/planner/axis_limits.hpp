#pragma once
// The kinematic limits of one axis. Velocity and acceleration have separate bounds for each
// direction (min_* < 0 < max_*), so a slower retract or a gentler deceleration can be asked for;
// the jerk bound is symmetric.

namespace cellctl::planner {

// A plain aggregate (AxisLimits{} is zero; no default member values): limits held for later
// (an axis's, a trajectory's per axis) are then not zeroed on every plan before they are set.
struct AxisLimits {
  double max_velocity;
  double min_velocity;  // < 0
  double max_acceleration;
  double min_acceleration;  // < 0
  double jerk;

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

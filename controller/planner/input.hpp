#pragma once
// What the planner is asked (Input) and what it answers each cycle (Output), for N axes.
// Input prints itself (operator<<, to_string) so a refused plan can say exactly what was asked.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>

namespace cellctl::planner {

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

// Eigen sizes are int, std::array sizes are size_t.
template <int N>
using AxisArray = std::array<bool, static_cast<std::size_t>(N)>;

enum class Synchronization : std::uint8_t {
  time,   // all axes arrive together at the earliest common duration, each on its own profile
  phase,  // a straight line in joint space (`path: line`), when the states allow it
  none,   // every axis on its own time-optimal profile
};

[[nodiscard]] constexpr std::string_view to_string(Synchronization s) noexcept {
  switch (s) {
    case Synchronization::time:
      return "time";
    case Synchronization::phase:
      return "phase";
    case Synchronization::none:
      return "none";
  }
  return "?";
}

template <int N>
struct Input {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  Vector<N> current_position = Vector<N>::Zero();
  Vector<N> current_velocity = Vector<N>::Zero();
  Vector<N> current_acceleration = Vector<N>::Zero();
  Vector<N> target_position = Vector<N>::Zero();
  Vector<N> target_velocity = Vector<N>::Zero();
  Vector<N> target_acceleration = Vector<N>::Zero();
  Vector<N> max_velocity = Vector<N>::Ones();
  Vector<N> max_acceleration = Vector<N>::Ones();
  Vector<N> max_jerk = Vector<N>::Ones();
  // The negative-direction bounds (< 0); unset (NaN) means minus the max.
  Vector<N> min_velocity = Vector<N>::Constant(kUnset);
  Vector<N> min_acceleration = Vector<N>::Constant(kUnset);
  // The travel: every position of the motion stays within it.
  Vector<N> min_position = Vector<N>::Constant(-kInf);
  Vector<N> max_position = Vector<N>::Constant(kInf);
  AxisArray<N> enabled = filled(true);
  Synchronization synchronization = Synchronization::time;

  friend bool operator==(const Input& a, const Input& b) noexcept {
    const auto same = [](const Vector<N>& x, const Vector<N>& y) {
      for (int i = 0; i < N; ++i) {
        if (!(x[i] == y[i] || (x[i] != x[i] && y[i] != y[i]))) return false;  // NaN equals NaN (unset)
      }
      return true;
    };
    return same(a.current_position, b.current_position) && same(a.current_velocity, b.current_velocity) &&
           same(a.current_acceleration, b.current_acceleration) &&
           same(a.target_position, b.target_position) && same(a.target_velocity, b.target_velocity) &&
           same(a.target_acceleration, b.target_acceleration) && same(a.max_velocity, b.max_velocity) &&
           same(a.max_acceleration, b.max_acceleration) && same(a.max_jerk, b.max_jerk) &&
           same(a.min_velocity, b.min_velocity) && same(a.min_acceleration, b.min_acceleration) &&
           same(a.min_position, b.min_position) && same(a.max_position, b.max_position) &&
           a.enabled == b.enabled && a.synchronization == b.synchronization;
  }

  // One line per axis: "axis 0: p 1 v 0 a 0 -> p 2 v 0 a 0; v [-1, 1] a [-2, 2] j 10; travel [-inf, inf]".
  friend std::ostream& operator<<(std::ostream& os, const Input& in) {
    os << "synchronization " << to_string(in.synchronization);
    for (int i = 0; i < N; ++i) {
      os << "\naxis " << i << ": ";
      if (!in.enabled[static_cast<std::size_t>(i)]) {
        os << "disabled";
        continue;
      }
      const double vmin = in.min_velocity[i] == in.min_velocity[i] ? in.min_velocity[i] : -in.max_velocity[i];
      const double amin =
          in.min_acceleration[i] == in.min_acceleration[i] ? in.min_acceleration[i] : -in.max_acceleration[i];
      os << "p " << in.current_position[i] << " v " << in.current_velocity[i] << " a "
         << in.current_acceleration[i] << " -> p " << in.target_position[i] << " v " << in.target_velocity[i]
         << " a " << in.target_acceleration[i] << "; v [" << vmin << ", " << in.max_velocity[i] << "] a ["
         << amin << ", " << in.max_acceleration[i] << "] j " << in.max_jerk[i] << "; travel ["
         << in.min_position[i] << ", " << in.max_position[i] << "]";
    }
    return os;
  }

 private:
  static constexpr AxisArray<N> filled(bool value) noexcept {
    AxisArray<N> a{};
    a.fill(value);
    return a;
  }
};

template <int N>
[[nodiscard]] std::string to_string(const Input<N>& in) {
  std::ostringstream os;
  os.precision(17);
  os << in;
  return os.str();
}

// With Result::outside_travel: which end of the axis's travel (min_position or max_position) the
// motion leaves, and by how much (> 0) — what the operator needs to move the target or the limit.
struct TravelExcess {
  bool beyond_max = false;  // false: below min_position
  double by = 0.0;
};

// With Result::target_outside_limits: which bound the target state breaks and by how much (> 0).
// The *_on_arrival ones: a target velocity within its limits, but with an acceleration that could
// only have been ramped in (at full jerk, from zero) from a velocity beyond that limit.
enum class TargetLimit : std::uint8_t {
  none,
  max_velocity,
  min_velocity,
  max_acceleration,
  min_acceleration,
  max_velocity_on_arrival,
  min_velocity_on_arrival,
};

[[nodiscard]] constexpr std::string_view to_string(TargetLimit l) noexcept {
  switch (l) {
    case TargetLimit::none:
      return "none";
    case TargetLimit::max_velocity:
      return "max_velocity";
    case TargetLimit::min_velocity:
      return "min_velocity";
    case TargetLimit::max_acceleration:
      return "max_acceleration";
    case TargetLimit::min_acceleration:
      return "min_acceleration";
    case TargetLimit::max_velocity_on_arrival:
      return "max_velocity on the way into the target acceleration";
    case TargetLimit::min_velocity_on_arrival:
      return "min_velocity on the way into the target acceleration";
  }
  return "?";
}

struct TargetExcess {
  TargetLimit limit = TargetLimit::none;
  double by = 0.0;
};

template <int N>
struct Output {
  Vector<N> new_position = Vector<N>::Zero();
  Vector<N> new_velocity = Vector<N>::Zero();
  Vector<N> new_acceleration = Vector<N>::Zero();
  Vector<N> new_jerk = Vector<N>::Zero();
  double time = 0.0;             // of the new state, since the current trajectory was planned [s]
  double duration = 0.0;         // of the whole current trajectory, a brake before it included [s]
  bool done = false;             // the new state is the target
  bool new_calculation = false;  // this cycle planned a new trajectory
  int error_axis = -1;           // the axis named by an error Result, -1 otherwise
  TravelExcess travel_excess;    // with Result::outside_travel (see TravelExcess)
  TargetExcess target_excess;    // with Result::target_outside_limits (see TargetExcess)
  // Set when phase synchronisation was asked for but the states are not on one line: the
  // trajectory is time-synchronised instead (a static string, empty otherwise).
  std::string_view note;

  // The new state becomes the next current state: the normal way to step the planner.
  void pass_to_input(Input<N>& in) const noexcept {
    in.current_position = new_position;
    in.current_velocity = new_velocity;
    in.current_acceleration = new_acceleration;
  }
};

}  // namespace cellctl::planner

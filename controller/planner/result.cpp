#include "planner/result.hpp"

namespace cellctl::planner {

std::string_view to_string(Result r) noexcept {
  switch (r) {
    case Result::working:
      return "working";
    case Result::finished:
      return "finished";
    case Result::invalid_state:
      return "invalid state: a current position, velocity, acceleration or target is not finite";
    case Result::invalid_limits:
      return "invalid limits: max velocity, acceleration and jerk must be finite and > 0, min velocity and "
             "acceleration finite and < 0 (or unset), min position <= max position";
    case Result::target_outside_limits:
      return "target outside the limits: its velocity or acceleration is beyond them or bound to cross them";
    case Result::unsupported_target:
      return "unsupported target: the profile to this target state misses it by more than the planner "
             "accepts (a planner defect: please report the input)";
    case Result::outside_travel:
      return "outside the travel: the target, or the motion to it, leaves the axis's position limits (by "
             "Output::travel_excess)";
  }
  return "unknown result";
}

}  // namespace cellctl::planner

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
      return "invalid limits: max velocity, acceleration and jerk must be finite and > 0";
  }
  return "unknown result";
}

}  // namespace cellctl::planner

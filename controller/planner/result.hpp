#pragma once
// What one planner step reports. Errors carry their reason here and the offending axis in
// Output::error_axis; the planner never throws once constructed.

#include <string_view>

namespace cellctl::planner {

enum class Result {
  working,         // the new state is on the way to the target
  finished,        // the new state is the target, at rest
  invalid_state,   // a current position/velocity/acceleration or target is not finite
  invalid_limits,  // a max velocity/acceleration/jerk of an enabled axis is not finite and > 0
};

[[nodiscard]] constexpr bool is_error(Result r) noexcept {
  return r == Result::invalid_state || r == Result::invalid_limits;
}

[[nodiscard]] std::string_view to_string(Result r) noexcept;

}  // namespace cellctl::planner

#pragma once
// What one planner step reports. Errors carry their reason here and the offending axis in
// Output::error_axis; the planner never throws once constructed.

#include <string_view>

namespace cellctl::planner {

enum class Result {
  working,                // the new state is on the way to the target
  finished,               // the new state is the target
  invalid_state,          // a current position/velocity/acceleration or target is not finite
  invalid_limits,         // a limit of an enabled axis is not finite, not of the right sign, or min > max
  target_outside_limits,  // a target velocity/acceleration is beyond the limits or bound to cross them
  outside_travel,         // the target, or the motion to it (overshoot included), leaves the travel
  unsupported_target,     // the profile built would miss the target (a safety net; not seen in tests)
};

[[nodiscard]] constexpr bool is_error(Result r) noexcept {
  return r != Result::working && r != Result::finished;
}

[[nodiscard]] std::string_view to_string(Result r) noexcept;

}  // namespace cellctl::planner

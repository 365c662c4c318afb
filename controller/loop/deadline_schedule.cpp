#include "loop/deadline_schedule.hpp"

namespace cellctl::loop {

NextDeadline next_deadline(link::TimePoint deadline, link::TimePoint end, link::Duration period) noexcept {
  const link::Duration elapsed = end - deadline;
  if (elapsed <= period) return {deadline + period, 0};
  // Ending exactly on a grid point is in time for it: only points strictly before `end` are missed.
  const auto missed = static_cast<std::uint64_t>((elapsed - link::Duration{1}) / period);
  return {deadline + period * static_cast<std::int64_t>(missed + 1), missed};
}

}  // namespace cellctl::loop

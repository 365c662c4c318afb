#pragma once
// Skip-ahead after an overrun: the next deadline is the first one of the period grid after the end
// of the cycle. Deadlines already passed are counted as missed, never run in a catch-up burst.

#include <cstdint>

#include "link/clock.hpp"

namespace cellctl::loop {

struct NextDeadline {
  link::TimePoint deadline;
  std::uint64_t missed = 0;  // grid deadlines strictly before the cycle's end
};

// deadline: the one the cycle started on; end: when it finished; period > 0.
[[nodiscard]] NextDeadline next_deadline(link::TimePoint deadline, link::TimePoint end,
                                         link::Duration period) noexcept;

}  // namespace cellctl::loop

#include "loop/cycle_waiter.hpp"

#include <cerrno>
#include <ctime>

namespace cellctl::loop {

void MonotonicWaiter::wait_until(link::TimePoint deadline) noexcept {
  // link::MonotonicClock counts from CLOCK_MONOTONIC's own origin, so the time point maps directly.
  const auto ns = deadline.time_since_epoch().count();
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace cellctl::loop

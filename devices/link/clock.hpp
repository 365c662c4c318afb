#pragma once
// The injected clock. Sessions, emulators and SimLink read time only through a Clock, so the same
// code runs on the monotonic clock in production and on a virtual clock in tests and dry runs.

#include <chrono>

namespace cellctl::link {

using Duration = std::chrono::nanoseconds;
using TimePoint = std::chrono::time_point<std::chrono::steady_clock, Duration>;

class Clock {
 public:
  virtual ~Clock() = default;
  [[nodiscard]] virtual TimePoint now() const noexcept = 0;
};

// CLOCK_MONOTONIC: never jumps with wall-clock changes.
class MonotonicClock final : public Clock {
 public:
  [[nodiscard]] TimePoint now() const noexcept override;
};

// Time that moves only when the caller says so: deterministic tests and faster-than-real-time runs.
class VirtualClock final : public Clock {
 public:
  explicit VirtualClock(TimePoint start = TimePoint{}) noexcept : now_(start) {}
  [[nodiscard]] TimePoint now() const noexcept override { return now_; }
  void advance(Duration d) noexcept { now_ += d; }
  // Moves to t; a t in the past is ignored (time never runs backwards).
  void advance_to(TimePoint t) noexcept {
    if (t > now_) now_ = t;
  }

 private:
  TimePoint now_;
};

// Seconds as a double, for statistics and messages (not for scheduling).
[[nodiscard]] inline double to_seconds(Duration d) noexcept {
  return std::chrono::duration<double>(d).count();
}

// The one conversion between a Duration and the millisecond figures of configs, limits and messages.
[[nodiscard]] inline double to_milliseconds(Duration d) noexcept {
  return std::chrono::duration<double, std::milli>(d).count();
}
// Rounded to the nearest nanosecond (a cast would truncate 0.3 ms to 299999 ns).
[[nodiscard]] inline Duration milliseconds(double ms) noexcept {
  return std::chrono::round<Duration>(std::chrono::duration<double, std::milli>(ms));
}

}  // namespace cellctl::link

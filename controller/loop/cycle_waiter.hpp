#pragma once
// How the loop waits for the next absolute deadline. One Loop runs on either: the real monotonic
// clock (sleeps until the deadline) or a virtual clock (jumps to the deadline: as fast as the
// machine allows). The waiter must match the loop's clock: MonotonicWaiter with
// link::MonotonicClock, VirtualWaiter with the VirtualClock it was given.

#include "link/clock.hpp"

namespace cellctl::loop {

class CycleWaiter {
 public:
  virtual ~CycleWaiter() = default;
  // Returns at or after `deadline`; at once if it has passed.
  virtual void wait_until(link::TimePoint deadline) noexcept = 0;
};

// clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME): absolute, so the wake-up never drifts with the
// time spent computing; resumes after a signal interrupts it.
class MonotonicWaiter final : public CycleWaiter {
 public:
  void wait_until(link::TimePoint deadline) noexcept override;
};

class VirtualWaiter final : public CycleWaiter {
 public:
  explicit VirtualWaiter(link::VirtualClock& clock) noexcept : clock_(clock) {}
  void wait_until(link::TimePoint deadline) noexcept override { clock_.advance_to(deadline); }

 private:
  link::VirtualClock& clock_;
};

}  // namespace cellctl::loop

#pragma once
// Heap allocations of the loop's thread from the first cycle the supervisor is in Execute to the
// first one it is not (the recipe's execution, after the devices are up). Fed from CellRun's cycle
// hook, which runs at the start of a cycle, so the window holds whole cycles. The cycles before it
// (start-up: sessions activating) and after it (completing, devices closing) are counted apart:
// they may allocate, and a non-zero start-up count also shows that the counter sees this thread.
// Needs support/allocation_counter.cpp linked into the executable.

#include <cstddef>
#include <cstdint>

#include "supervisor/packml.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::testing {

struct ExecuteWindow {
  // Set to 1 while the window is open, for a debugger's breakpoint condition (may be null).
  volatile int* in_window = nullptr;

  bool seen = false;
  bool open = false;
  bool closed = false;
  std::uint64_t cycles = 0;
  std::size_t at_first = 0;
  std::size_t at_open = 0;
  std::size_t at_close = 0;
  std::size_t at_last = 0;
  supervisor::State ended_in = supervisor::State::idle;

  void on_cycle(supervisor::State s) noexcept {
    const std::size_t now = thread_allocation_count();
    if (!seen) at_first = now;
    seen = true;
    at_last = now;
    if (!open && !closed && s == supervisor::State::execute) {
      open = true;
      at_open = now;
      if (in_window) *in_window = 1;
    } else if (open && s != supervisor::State::execute) {
      open = false;
      closed = true;
      at_close = now;
      ended_in = s;
      if (in_window) *in_window = 0;
    }
    if (open) ++cycles;
  }
  [[nodiscard]] std::size_t allocations() const noexcept { return closed ? at_close - at_open : 0; }
  [[nodiscard]] std::size_t start_up() const noexcept { return at_open - at_first; }
  [[nodiscard]] std::size_t after() const noexcept { return closed ? at_last - at_close : 0; }
};

}  // namespace cellctl::testing

#pragma once
// Steps something non-blocking (a session, an emulator) on the real clock until a condition holds or a
// deadline passes. For commissioning commands and `cellctl emulate`, which are not the control loop:
// between steps the thread sleeps a little, which is fine there and never done in the cycle.

#include <atomic>
#include <thread>

#include "link/clock.hpp"

namespace cellctl::cli {

// Set by SIGINT (Ctrl-C) and SIGTERM (installed by main); every drive loop ends early on either.
extern std::atomic<bool> g_interrupted;
extern std::atomic<bool> g_terminated;

template <class Step, class Done>
bool drive_until(const link::Clock& clock, link::Duration timeout, Step&& step, Done&& done,
                 link::Duration pause = std::chrono::microseconds(200)) {
  const auto deadline = clock.now() + timeout;
  while (!g_interrupted.load() && !g_terminated.load()) {
    const auto now = clock.now();
    step(now);
    if (done()) return true;
    if (now >= deadline) return false;
    std::this_thread::sleep_for(pause);
  }
  return false;
}

}  // namespace cellctl::cli

#pragma once
// Runs non-blocking parts (sessions, emulators) on a virtual clock: step(now) is called at every
// tick of `dt` until done() holds or `limit` of virtual time has passed. Deterministic and as fast
// as the machine allows; tests never sleep.

#include "link/clock.hpp"

namespace cellctl::testing {

template <class Step, class Done>
bool run_until(link::VirtualClock& clock, link::Duration dt, link::Duration limit, Step&& step, Done&& done) {
  const auto deadline = clock.now() + limit;
  while (clock.now() < deadline) {
    step(clock.now());
    if (done()) return true;
    clock.advance(dt);
  }
  step(clock.now());
  return done();
}

template <class Step>
void run_for(link::VirtualClock& clock, link::Duration dt, link::Duration span, Step&& step) {
  (void)run_until(clock, dt, span, step, [] { return false; });
}

}  // namespace cellctl::testing

#pragma once
// A session and an emulator on the two ends of a SimLink at 38400 8N1, on one virtual clock.

#include "link/sim_link.hpp"
#include "scu/emulator.hpp"
#include "scu/session.hpp"
#include "support/virtual_time.hpp"

namespace cellctl::scu::testing {

inline plant::ActuatorParams test_physics() {
  plant::ActuatorParams p;
  p.stroke_mm = 200.0;
  p.max_speed_mm_s = 20.0;
  p.ramp_mm_s2 = 40.0;
  p.min_speed_mm_s = 0.8;
  return p;
}

inline SessionConfig session_config(int actuators) {
  SessionConfig c;
  c.actuators = 0;
  for (int a = 0; a < actuators; ++a) c.actuators.set(static_cast<std::size_t>(a));
  c.functions = scp11(c.actuators);
  return c;
}

struct Rig {
  explicit Rig(int actuators = 1, SessionConfig sc = {}, bool default_session = true)
      : emulator(sim.device(), scp11_emulator(actuators, test_physics(), 100.0)),
        session(sim.master(), default_session ? session_config(actuators) : sc) {}

  void step(link::TimePoint now) {
    emulator.poll(now);
    session.receive(now);
    session.transmit(now);
  }
  template <class Done>
  bool run_until(link::Duration limit, Done&& done, link::Duration dt = std::chrono::milliseconds(1)) {
    return cellctl::testing::run_until(
        clock, dt, limit, [this](link::TimePoint t) { step(t); }, done);
  }
  bool activate() {
    session.activate(clock.now());
    return run_until(std::chrono::seconds(1),
                     [this] { return session.lifecycle() == link::Lifecycle::active; });
  }

  link::VirtualClock clock;
  link::SimLink sim{clock, link::line_8n1(38400), "scu"};
  Emulator emulator;
  Session session;
};

}  // namespace cellctl::scu::testing

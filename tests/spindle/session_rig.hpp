#pragma once
// A spindle session and its emulator on one SimLink, stepped together on a virtual clock.

#include "link/sim_link.hpp"
#include "spindle/emulator.hpp"
#include "spindle/session.hpp"
#include "support/virtual_time.hpp"

namespace cellctl::spindle {

inline EmulatorConfig fast_test_emulator() {
  EmulatorConfig c;
  c.min_hz = 100.0;
  c.max_hz = 1000.0;
  c.ramp_up_hz_s = 400.0;  // 0 → 400 Hz in 1 s
  c.ramp_down_hz_s = 800.0;
  c.converter_type = 4625;
  c.firmware = 0x0433;
  c.serial_number = 20240117;
  c.converter_hours = 269.5;
  c.motor_hours = 6.0;
  return c;
}

struct SessionRig {
  explicit SessionRig(SessionConfig session_config = {},
                      EmulatorConfig emulator_config = fast_test_emulator())
      : emulator(sim.device(), emulator_config), session(sim.master(), session_config) {}

  void step(link::TimePoint now) {
    emulator.poll(now);
    session.receive(now);
    session.transmit(now);
    state = session.lifecycle();
  }
  template <class Done>
  bool run_until(link::Duration limit, Done&& done) {
    return testing::run_until(
        clock, std::chrono::milliseconds(1), limit, [this](auto now) { step(now); },
        std::forward<Done>(done));
  }
  void run_for(link::Duration span) {
    testing::run_for(clock, std::chrono::milliseconds(1), span, [this](auto now) { step(now); });
  }
  bool activate() {
    session.activate(clock.now());
    return run_until(std::chrono::seconds(1), [this] {
      return state == link::Lifecycle::active && session.snapshot().status_valid &&
             session.snapshot().values_valid;
    });
  }

  link::VirtualClock clock;
  link::SimLink sim{clock, link::line_8n1(38400), "sim:spindle"};
  Emulator emulator;
  Session session;
  link::Lifecycle state = link::Lifecycle::inactive;
};

}  // namespace cellctl::spindle

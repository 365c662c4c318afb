#pragma once
// encoder::Session (DP master) and encoder::Emulator (DP slave) over SimLink at 1.5 Mbaud 8E1 in
// virtual time, stepped from event to event; the emulated axis moves at a set speed.

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>

#include "encoder/emulator.hpp"
#include "encoder/session.hpp"
#include "link/sim_link.hpp"
#include "plant/shaft.hpp"

namespace cellctl::encoder::testing {

using namespace std::chrono_literals;

struct Rig {
  // `functionality` is the master's choice; the emulator takes it from Set_Prm/Chk_Cfg.
  explicit Rig(Functionality functionality = Functionality::scancon22, std::uint8_t emu_address = 5,
               std::filesystem::path state_file = {})
      : sim(clock, link::line_8e1(1'500'000)),
        shaft(plant::ShaftParams{4.0, 0.0, 0.0}, [this] { return axis_mm(); }) {
    emu_config.address = emu_address;
    emu_config.identity.physical = PhysicalResolution{8192, 4096};
    emu_config.state_file = std::move(state_file);
    session_config.station_address = emu_address;
    session_config.parameters.functionality = functionality;
    session_config.physical = PhysicalResolution{8192, 4096};
    session_config.mm_per_revolution = 4.0;
    session_config.bus.master_address = 2;
    session_config.bus.wd_fact_1 = 2;
    session_config.bus.wd_fact_2 = 5;  // 100 ms response watchdog
    session_config.bus.lost_slave_time = 50ms;
    make_emulator();
  }
  void make_emulator() { emulator = std::make_unique<Emulator>(sim.device(), emu_config, shaft); }
  Session& start() {
    session = std::make_unique<Session>(sim.master(), session_config);
    session->activate(clock.now());
    return *session;
  }
  double axis_mm() const {
    return axis_start_mm + axis_speed_mm_s * link::to_seconds(clock.now() - moving_since);
  }
  void move_to(double mm) {
    axis_start_mm = mm;
    axis_speed_mm_s = 0;
  }

  // Steps both sides from event to event (next octet, next deadline, at most 1 ms) until `done`.
  template <class Done>
  bool run_until(Done done, link::Duration limit, bool poll_master = true) {
    const auto deadline = clock.now() + limit;
    while (clock.now() < deadline) {
      const auto now = clock.now();
      if (poll_master && session) poll_session(now);
      emulator->poll(now);
      if (done()) return true;
      auto next = now + 1ms;
      for (auto d : {sim.next_delivery(), session && poll_master ? session->next_deadline() : std::nullopt,
                     emulator->next_deadline()})
        if (d) next = std::min(next, std::max(*d, now + 1us));
      clock.advance_to(next);
    }
    return done();
  }
  void run_for(link::Duration d, bool poll_master = true) {
    (void)run_until([] { return false; }, d, poll_master);
  }
  // The session's poll alone is counted: the emulator (the device side) is not under test there.
  void poll_session(link::TimePoint now) {
    const std::size_t before = allocation_count ? allocation_count() : 0;
    session->receive(now);
    session->transmit(now);
    if (allocation_count) session_poll_allocations += allocation_count() - before;
  }
  bool exchanging() const { return session->snapshot().data_exchange && session->snapshot().exchanges > 2; }

  link::VirtualClock clock;
  link::SimLink sim;
  double axis_start_mm = 0.0;
  double axis_speed_mm_s = 0.0;
  link::TimePoint moving_since{};
  plant::Shaft shaft;
  EmulatorConfig emu_config;
  SessionConfig session_config;
  std::unique_ptr<Emulator> emulator;
  std::unique_ptr<Session> session;
  // Set by a test that counts allocations (tests/support/allocation_counter.hpp).
  std::function<std::size_t()> allocation_count;
  std::size_t session_poll_allocations = 0;
};

}  // namespace cellctl::encoder::testing

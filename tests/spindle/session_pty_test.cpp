// Once over a real pseudo-terminal: the session on SerialLink, the emulator on PtyPair, both on the
// monotonic clock, in a bounded loop that waits for a condition (never a fixed sleep).

#include <gtest/gtest.h>

#include <thread>

#include "link/pty_pair.hpp"
#include "link/serial_link.hpp"
#include "spindle/emulator.hpp"
#include "spindle/session.hpp"

namespace cellctl::spindle {
namespace {

using namespace std::chrono_literals;

TEST(SpindleSessionPty, StartsToSpeedAndStopsOverAPseudoTerminal) {
  link::PtyPair pty("spindle");
  auto serial = link::SerialLink::open(pty.peer_path(), link::line_8n1(38400));
  EmulatorConfig emulator_config;
  emulator_config.ramp_up_hz_s = emulator_config.ramp_down_hz_s = 2000.0;
  Emulator emulator(pty.device(), emulator_config);
  Session session(*serial, SessionConfig{});
  link::MonotonicClock clock;
  link::Lifecycle state = link::Lifecycle::inactive;

  auto run_until = [&](auto done) {
    const auto deadline = clock.now() + 5s;
    while (clock.now() < deadline) {
      emulator.poll(clock.now());
      session.receive(clock.now());
      session.transmit(clock.now());
      state = session.lifecycle();
      if (done() || state == link::Lifecycle::fault) return done();
      std::this_thread::sleep_for(200us);
    }
    return done();
  };

  session.activate(clock.now());
  ASSERT_TRUE(run_until([&] { return state == link::Lifecycle::active; })) << session.fault_reason();
  ASSERT_TRUE(session.start(400.0));
  ASSERT_TRUE(run_until([&] { return session.snapshot().at_speed; })) << session.fault_reason();
  ASSERT_TRUE(session.stop());
  ASSERT_TRUE(run_until([&] { return session.snapshot().at_rest && !session.commands_pending(); }));
  EXPECT_EQ(session.health().bad_frames, 0u);
  EXPECT_GT(session.health().good_replies, 5u);
}

}  // namespace
}  // namespace cellctl::spindle

// The same move once over a real pseudo-terminal: Session on a SerialLink, Emulator on the PtyPair,
// both stepped on the monotonic clock in a bounded loop that waits for a condition.

#include <gtest/gtest.h>

#include <thread>

#include "link/clock.hpp"
#include "link/pty_pair.hpp"
#include "link/serial_link.hpp"
#include "scu/emulator.hpp"
#include "scu/session.hpp"
#include "scu_rig.hpp"

namespace cellctl::scu {
namespace {

using namespace std::chrono_literals;

TEST(ScuPty, MoveOverARealPseudoTerminal) {
  link::PtyPair pty("scu");
  auto serial = link::SerialLink::open(pty.peer_path(), link::line_8n1(38400));
  Emulator emulator(pty.device(), scp11_emulator(1, testing::test_physics(), 100.0));
  Session session(*serial, testing::session_config(1));
  const link::MonotonicClock clock;

  const auto run_until = [&](link::Duration limit, auto&& done) {
    const auto deadline = clock.now() + limit;
    while (clock.now() < deadline) {
      const auto now = clock.now();
      emulator.poll(now);
      session.receive(now);
      session.transmit(now);
      if (done()) return true;
      std::this_thread::sleep_for(200us);
    }
    return false;
  };

  session.activate(clock.now());
  ASSERT_TRUE(run_until(3s, [&] { return session.lifecycle() == link::Lifecycle::active; }))
      << session.fault_reason();
  const ActuatorTarget target[] = {{1, 3.0}};  // 3 mm at 20 mm/s: well under a second of motion
  ASSERT_TRUE(session.move_to(1, target, 20.0, true));
  ASSERT_TRUE(run_until(5s,
                        [&] {
                          const auto& f = session.snapshot().functions[0];
                          return f.outcome == MoveOutcome::arrived && !f.execution_open;
                        }))
      << to_string(session.snapshot().functions[0].outcome) << " " << session.fault_reason();
  EXPECT_FALSE(emulator.execution_open(1)) << "RS reached the SCU";
  EXPECT_NEAR(session.snapshot().actuators[0].position_edges, 300, 1);
  session.deactivate(clock.now());
  ASSERT_TRUE(run_until(3s, [&] { return session.lifecycle() == link::Lifecycle::inactive; }));
  EXPECT_FALSE(emulator.remote_open());
  EXPECT_EQ(session.health().bad_frames, 0u);
}

}  // namespace
}  // namespace cellctl::scu

// The same master and slave over a real pseudo-terminal (SerialLink ⇄ PtyPair) on the monotonic
// clock: the framing survives a tty, whatever pieces the kernel delivers octets in. Bounded loop that
// waits for a condition; the slot time is widened because a pty is scheduled, not clocked.

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "bus_fixture.hpp"
#include "link/pty_pair.hpp"
#include "link/serial_link.hpp"

namespace cellctl::profibus::testing {
namespace {

TEST(DpPty, StartsUpAndExchangesDataOverAPseudoTerminal) {
  link::PtyPair pty("dp-slave");
  auto serial = link::SerialLink::open(pty.peer_path(), link::line_8e1(1'500'000));
  DpMasterConfig config = master_config();
  config.slot_time_bits = 150'000;  // 100 ms at 1.5 Mbaud: scheduling latency, not line time
  config.lost_slave_time = std::chrono::milliseconds(500);
  config.wd_fact_1 = 10;  // 1 s slave watchdog
  config.wd_fact_2 = 10;
  config.data_exchange_period = std::chrono::milliseconds(2);
  DpMaster master(*serial, config, slave_setup());
  TestBehaviour behaviour;
  DpSlave slave(pty.device(), DpSlaveConfig{kStation, kIdent}, behaviour);
  const std::array<std::uint8_t, 4> out{0xde, 0xad, 0xbe, 0xef};
  link::MonotonicClock clock;
  master.activate(clock.now());
  ASSERT_TRUE(master.set_outputs(out));

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (master.stats().data_exchanges < 20 && std::chrono::steady_clock::now() < deadline) {
    (void)master.poll(clock.now());
    slave.poll(clock.now());
    std::this_thread::yield();
  }
  ASSERT_GE(master.stats().data_exchanges, 20u) << "state " << to_string(master.dp_state());
  EXPECT_EQ(master.lifecycle(), link::Lifecycle::active);
  EXPECT_EQ(slave.state(), DpSlaveState::data_exchange);
  EXPECT_EQ(behaviour.last_outputs, (std::vector<std::uint8_t>{0xde, 0xad, 0xbe, 0xef}));
  EXPECT_EQ(master.health().bad_frames, 0u);
  EXPECT_EQ(slave.counters().bad_frames, 0u);
  EXPECT_EQ(master.stats().startups, 1u);
}

}  // namespace
}  // namespace cellctl::profibus::testing

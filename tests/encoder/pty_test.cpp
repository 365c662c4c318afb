// Session and Emulator once over a real pseudo-terminal (SerialLink ⇄ PtyPair) on the monotonic
// clock: a bounded loop that waits for data exchange and a preset, never a blind sleep.
#include <gtest/gtest.h>

#include <thread>

#include "encoder/emulator.hpp"
#include "encoder/session.hpp"
#include "link/pty_pair.hpp"
#include "link/serial_link.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;

TEST(EncoderPty, DataExchangeAndPresetOverAPseudoTerminal) {
  const auto line = link::line_8e1(19200);
  link::PtyPair pty("encoder");
  auto serial = link::SerialLink::open(pty.peer_path(), line);
  plant::Shaft shaft(plant::ShaftParams{4.0, 0.0, 0.0}, [] { return 8.0; });
  EmulatorConfig ec;
  ec.address = 3;
  ec.line = line;
  Emulator emulator(pty.device(), ec, shaft);
  SessionConfig sc;
  sc.station_address = 3;
  sc.mm_per_revolution = 4.0;
  sc.bus.line = line;
  sc.bus.slot_time_bits = 2000;  // a pty adds scheduling latency the bit times do not know about
  sc.bus.max_retries = 3;
  sc.bus.data_exchange_period = 2ms;
  sc.bus.lost_slave_time = 1s;
  Session session(*serial, sc);
  link::MonotonicClock clock;
  session.activate(clock.now());

  const auto run_until = [&](auto done) {
    const auto deadline = clock.now() + 5s;
    while (clock.now() < deadline) {
      session.receive(clock.now());
      session.transmit(clock.now());
      emulator.poll(clock.now());
      if (done()) return true;
      std::this_thread::yield();
    }
    return false;
  };
  ASSERT_TRUE(run_until([&] { return session.snapshot().data_exchange && session.snapshot().exchanges > 5; }))
      << session.fault_reason();
  EXPECT_EQ(session.snapshot().position_counts, 2u * 8192u);
  EXPECT_DOUBLE_EQ(session.snapshot().position_mm, 8.0);
  ASSERT_TRUE(session.preset(42));
  ASSERT_TRUE(run_until([&] { return session.snapshot().command.phase >= Handshake::Phase::done; }));
  EXPECT_EQ(session.snapshot().command.phase, Handshake::Phase::done) << session.snapshot().command.failure;
  const auto after = session.snapshot().exchanges;
  ASSERT_TRUE(run_until([&] { return session.snapshot().exchanges > after + 2; }));
  EXPECT_EQ(session.snapshot().position_counts, 42u);
}

}  // namespace
}  // namespace cellctl::encoder

// Once over a real pseudo-terminal: the session on SerialLink, the emulator on PtyPair, both on the
// monotonic clock, in a bounded loop that waits for a condition (never a fixed sleep).

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
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

// The converter's end of a cable that can be pulled and plugged into another adapter: the emulated
// converter lives on (and keeps turning) while its pseudo-terminal is gone.
class Cable final : public link::Link {
 public:
  link::IoResult read(std::span<std::uint8_t> b) override { return to_ ? to_->read(b) : link::IoResult{}; }
  link::IoResult write(std::span<const std::uint8_t> b) override {
    return to_ ? to_->write(b) : link::IoResult{b.size()};
  }
  [[nodiscard]] std::string describe() const override { return "cable"; }
  void plug(link::Link* to) noexcept { to_ = to; }

 private:
  link::Link* to_ = nullptr;
};

TEST(SpindleSessionPty, PortLostWhileTurningIsOpenedAgainAndTheStopConfirmed) {
  // The port as a config names it: a fixed path (udev's symlink) to whatever adapter is plugged in.
  const auto port =
      std::filesystem::temp_directory_path() / ("cellctl-spindle-port-" + std::to_string(::getpid()));
  auto adapter = std::make_unique<link::PtyPair>("spindle", port);
  auto serial = link::SerialLink::open(port.string(), link::line_8n1(38400));
  Cable cable;
  cable.plug(&adapter->device());
  EmulatorConfig emulator_config;
  emulator_config.ramp_up_hz_s = emulator_config.ramp_down_hz_s = 2000.0;
  Emulator converter(cable, emulator_config);
  Session session(*serial, SessionConfig{});
  link::MonotonicClock clock;

  auto run_until = [&](auto done) {
    const auto deadline = clock.now() + 5s;
    while (clock.now() < deadline) {
      converter.poll(clock.now());
      session.receive(clock.now());
      session.transmit(clock.now());
      if (done()) return true;
      std::this_thread::sleep_for(200us);
    }
    return done();
  };

  session.activate(clock.now());
  ASSERT_TRUE(run_until([&] { return session.lifecycle() == link::Lifecycle::active; }))
      << session.fault_reason();
  ASSERT_TRUE(session.start(400.0));
  ASSERT_TRUE(run_until([&] { return session.snapshot().at_speed; })) << session.fault_reason();

  // The adapter is pulled: the session's port hangs up, the converter turns on.
  cable.plug(nullptr);
  adapter.reset();
  ASSERT_TRUE(run_until([&] { return session.lifecycle() == link::Lifecycle::fault; }));
  EXPECT_NE(session.fault_reason().find("closed"), std::string::npos) << session.fault_reason();
  EXPECT_FALSE(serial->reopen().ok()) << "opened a port that is not there";
  EXPECT_GT(converter.motor().frequency_hz(), 300.0) << "the converter has no watchdog: it keeps turning";

  // Plugged in again (a new pseudo-terminal behind the same path): reopened, activated, stopped.
  adapter = std::make_unique<link::PtyPair>("spindle", port);
  cable.plug(&adapter->device());
  ASSERT_TRUE(serial->reopen().ok());
  session.activate(clock.now());
  ASSERT_TRUE(run_until([&] { return session.lifecycle() == link::Lifecycle::active; }))
      << session.fault_reason();
  session.deactivate(clock.now());
  // Inactive only once a statusout after the stop's ACK reports STILLSTAND.
  ASSERT_TRUE(run_until([&] { return session.lifecycle() == link::Lifecycle::inactive; }))
      << session.fault_reason();
  EXPECT_TRUE(converter.motor().at_rest()) << converter.motor().frequency_hz() << " Hz";
  EXPECT_TRUE(session.snapshot().at_rest);
  cable.plug(nullptr);
}

}  // namespace
}  // namespace cellctl::spindle

// The device boundary on simulated lines and a virtual clock: the runtime's cycle (receive → state →
// decide → apply → transmit) puts a stop decided in cycle k on the wire in cycle k — the SCU's
// emergency stop F20 and the spindle's stop — whenever the half-duplex line is free in that cycle.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "link/sim_link.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/emulated_cell.hpp"
#include "scu/codec.hpp"
#include "scu/data_list.hpp"
#include "spindle/codec.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

// The session's end of a line, recording what is written to it and in which cycle.
class RecordingLink final : public link::Link {
 public:
  explicit RecordingLink(link::Link& inner) : inner_(inner) {}
  link::IoResult read(std::span<std::uint8_t> buffer) override { return inner_.read(buffer); }
  link::IoResult write(std::span<const std::uint8_t> bytes) override {
    const auto r = inner_.write(bytes);
    written_.insert(written_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(r.count));
    return r;
  }
  [[nodiscard]] std::string describe() const override { return inner_.describe(); }

  void mark() { mark_ = written_.size(); }
  [[nodiscard]] std::size_t size() const { return written_.size(); }
  // Where `telegram` was first written at or after byte `from` (npos: not at all).
  [[nodiscard]] std::size_t find(std::span<const std::uint8_t> telegram, std::size_t from) const {
    const auto begin = written_.begin() + static_cast<std::ptrdiff_t>(from);
    const auto it = std::search(begin, written_.end(), telegram.begin(), telegram.end());
    return it == written_.end() ? std::string::npos : static_cast<std::size_t>(it - written_.begin());
  }
  // Whether `telegram` was written since mark().
  [[nodiscard]] bool wrote_since_mark(std::span<const std::uint8_t> telegram) const {
    const auto from = written_.begin() + static_cast<std::ptrdiff_t>(mark_);
    return std::search(from, written_.end(), telegram.begin(), telegram.end()) != written_.end();
  }

 private:
  link::Link& inner_;
  std::vector<std::uint8_t> written_;
  std::size_t mark_ = 0;
};

class Boundary : public ::testing::Test {
 protected:
  Boundary()
      : cell_(config::load_cell_config(CELLCTL_SOURCE_DIR "/config/cell.yaml")),
        setup_(emulation::load_emulator_setup(cell_)),
        scu_line_(clock_, cell_.scu->port.line, "scu"),
        spindle_line_(clock_, cell_.spindle->port.line, "spindle"),
        scu_rec_(scu_line_.master()),
        spindle_rec_(spindle_line_.master()),
        emulated_(cell_, setup_, runtime::DeviceLinks{&scu_line_.device(), &spindle_line_.device()}),
        links_{&scu_rec_, &spindle_rec_},
        devices_(cell_, links_, {}) {}

  // One control cycle as CellRun runs it, with `decide` as the supervisor.
  template <class Decide>
  void cycle(Decide&& decide) {
    const auto now = clock_.now();
    emulated_.poll(now);
    devices_.receive(now);
    devices_.read(now, state_);
    decide();
    scu_rec_.mark();
    spindle_rec_.mark();
    devices_.apply(intents_);
    devices_.transmit(now);
    clock_.advance(1ms);
  }
  template <class Done>
  bool cycle_until(Done&& done, int limit = 5000) {
    for (int i = 0; i < limit; ++i) {
      cycle([] {});
      if (done()) return true;
    }
    return false;
  }

  config::CellConfig cell_;
  emulation::EmulatorSetup setup_;
  link::VirtualClock clock_;
  link::SimLink scu_line_;
  link::SimLink spindle_line_;
  RecordingLink scu_rec_;
  RecordingLink spindle_rec_;
  runtime::EmulatedCell emulated_;
  std::array<link::Link*, 2> links_;  // the SCU's and the spindle's slots, the encoder left out
  runtime::CellDevices devices_;
  cell::CellState state_;
  cell::Intents intents_;
};

TEST_F(Boundary, AnEmergencyStopDecidedInCycleKIsOnTheScuLineInCycleK) {
  devices_.activate(clock_.now());
  ASSERT_TRUE(cycle_until([&] { return state_.links[0].active && state_.axes[0].present; }));
  intents_.axes[0] = {.move_id = 1, .move = true, .target_mm = 150.0, .speed_mm_s = 10.0, .soft = true};
  ASSERT_TRUE(cycle_until([&] { return state_.axes[0].moving; }));

  scu::RequestBytes f20;
  ASSERT_TRUE(scu::encode_request(
      scu::ExecuteRequest{scu::kEmergencyStopFnc, scu::kUnusedParam, scu::kUnusedParam}, f20));
  // The first cycle whose receive() left the line free decides the stop.
  auto* scu = devices_.scu();
  bool decided = false;
  for (int i = 0; i < 1000 && !decided; ++i) {
    cycle([&] {
      if (scu->awaiting_reply()) return;
      intents_.halt = cell::Halt::immediate;
      decided = true;
    });
  }
  ASSERT_TRUE(decided);
  EXPECT_TRUE(scu_rec_.wrote_since_mark(f20.view())) << "F20 left in the cycle that decided it";
  // And the SCU acts on it: the actuator stops.
  ASSERT_TRUE(cycle_until([&] { return scu->snapshot().emergency_stop_open; }, 200));
  EXPECT_TRUE(emulated_.scu()->emergency_stop_active());
}

// A new target for an axis whose RE is still open (a correction while it moves): the RE is closed by
// a soft RS first, as the manual wants of every RE, then the new remote position, speed and RE go
// out; the emulated SCU takes the actuator on from its speed.
class NewTargetWhileMoving : public Boundary {
 protected:
  // Activates, starts x towards 150 mm at 10 mm/s, waits for it to run at speed, then asks for 120.
  void retarget_x() {
    devices_.activate(clock_.now());
    ASSERT_TRUE(cycle_until([&] { return state_.links[0].active && state_.axes[0].present; }));
    intents_.axes[0] = {.move_id = 1, .move = true, .target_mm = 150.0, .speed_mm_s = 10.0, .soft = true};
    ASSERT_TRUE(cycle_until([&] { return emulated_.scu()->actuator(1).velocity_mm_s() >= 10.0 - 1e-9; }));
    ASSERT_TRUE(cycle_until([&] { return state_.axes[0].scu_mm > 20.0; }, 5000));
    from_ = scu_rec_.size();
    intents_.axes[0].move_id = 2;
    intents_.axes[0].target_mm = 120.0;
  }
  [[nodiscard]] std::size_t written(const scu::Request& r) const {
    scu::RequestBytes bytes;
    EXPECT_TRUE(scu::encode_request(r, bytes));
    return scu_rec_.find(bytes.view(), from_);
  }
  [[nodiscard]] std::uint8_t x_function() const {
    return static_cast<std::uint8_t>(cell_.axes[0].function - 1);
  }

  std::size_t from_ = 0;
};

TEST_F(NewTargetWhileMoving, GoesOutAsSoftRsThenRtAndReAndTheAxisGoesOnWithoutStopping) {
  retarget_x();
  double slowest = 10.0;
  ASSERT_TRUE(cycle_until(
      [&] {
        const auto& rod = emulated_.scu()->actuator(1);
        if (rod.position_mm() < 119.0) slowest = std::min(slowest, rod.velocity_mm_s());
        return !rod.moving();
      },
      20000));
  EXPECT_NEAR(emulated_.scu()->actuator(1).position_mm(), 120.0, 0.1) << "at the new target (SCU frame)";
  // 120 mm at the actuator's 10 edges per mm, little-endian.
  const std::array<std::uint8_t, 4> edges{0xB0, 0x04, 0x00, 0x00};
  const auto rs = written(scu::StopRequest{x_function(), scu::kSoftStartStop});
  const auto rt = written(scu::TransferRequest{scu::data_id::remote_position(cell_.axes[0].actuator), edges});
  const auto re = written(scu::ExecuteRequest{x_function(), 9, scu::kSoftStartStop});
  ASSERT_NE(rs, std::string::npos) << "no soft RS before the new move";
  ASSERT_NE(rt, std::string::npos) << "the new remote position never went out";
  ASSERT_NE(re, std::string::npos) << "the new RE never went out";
  EXPECT_LT(rs, rt);
  EXPECT_LT(rt, re);
  // The RS ramps the actuator down only until the RE: some 30 ms at 40 mm/s², about 1.2 mm/s.
  EXPECT_GT(slowest, 7.0) << "the actuator stopped (or nearly) before it went on";
}

// The RE is refused (as a stricter SCU might, while the actuator still ramps down): the RS has
// stopped the actuator, the move is reported refused, nothing runs on.
TEST_F(NewTargetWhileMoving, ARefusedReLeavesTheAxisStoppedAndTheMoveReportedRefused) {
  retarget_x();
  emulated_.scu()->refuse_next_requests(1, scu::Status::permission_error, scu::Command::execute);
  ASSERT_TRUE(cycle_until([&] { return state_.axes[0].move_refused; }, 2000));
  ASSERT_TRUE(cycle_until([&] { return !emulated_.scu()->actuator(1).moving(); }, 2000));
  EXPECT_LT(emulated_.scu()->actuator(1).position_mm(), 119.0) << "stopped short, where the RS left it";
}

// A category 0 stop while the soft RS of a new target still waits: besides the F20, the axis's own
// stop goes out fast too (were the F20 refused, only that stop would act).
TEST_F(NewTargetWhileMoving, ACategoryZeroStopMakesThePendingSoftRsFast) {
  retarget_x();
  cycle([] {});  // the soft RS is asked for
  intents_.halt = cell::Halt::immediate;
  // Behind the F20, within a few round trips.
  EXPECT_TRUE(cycle_until(
      [&] {
        return written(scu::StopRequest{x_function(), scu::kFastStartStop}) != std::string::npos;
      },
      200))
      << "category 0 left the axis on its soft stop";
}

TEST_F(Boundary, ASpindleStopDecidedInCycleKIsOnTheSpindleLineInCycleK) {
  devices_.activate(clock_.now());
  ASSERT_TRUE(cycle_until([&] { return state_.links[1].active; }));
  intents_.spindle = {.run = true, .frequency_hz = 400.0, .clockwise = true, .reset = false};
  ASSERT_TRUE(cycle_until([&] { return state_.spindle.at_speed; }));

  std::array<std::uint8_t, spindle::kMaxFrameLength> stop_frame{};
  const auto n = spindle::Codec::encode(spindle::Command{spindle::MsgId::cmd_stop}, stop_frame);
  const std::span<const std::uint8_t> stop(stop_frame.data(), n);
  auto* sp = devices_.spindle();
  bool decided = false;
  for (int i = 0; i < 1000 && !decided; ++i) {
    cycle([&] {
      if (sp->awaiting_reply()) return;
      intents_.spindle.run = false;
      decided = true;
    });
  }
  ASSERT_TRUE(decided);
  EXPECT_TRUE(spindle_rec_.wrote_since_mark(stop)) << "the stop left in the cycle that decided it";
  ASSERT_TRUE(cycle_until([&] { return state_.spindle.at_rest; }, 5000));
}

// Category 0 when the SCU refuses the F20: the refusal must not leave the axes running.
class RefusedEmergencyStop : public Boundary {
 protected:
  // Activates, starts x on a long move at 10 mm/s and waits for it to run at speed.
  void start_x() {
    devices_.activate(clock_.now());
    ASSERT_TRUE(cycle_until([&] { return state_.links[0].active && state_.axes[0].present; }));
    intents_.axes[0] = {.move_id = 1, .move = true, .target_mm = 150.0, .speed_mm_s = 10.0, .soft = true};
    ASSERT_TRUE(cycle_until([&] { return emulated_.scu()->actuator(1).velocity_mm_s() >= 10.0 - 1e-9; }));
  }
  void halt_immediately() {
    intents_.axes[0].move = false;
    intents_.halt = cell::Halt::immediate;
  }
};

TEST_F(RefusedEmergencyStop, ARefusedF20IsSentAgain) {
  start_x();
  emulated_.scu()->refuse_next_requests(1, scu::Status::permission_error, scu::Command::execute);
  halt_immediately();
  ASSERT_TRUE(cycle_until([&] { return devices_.scu()->snapshot().refusals > 0; }, 500));
  ASSERT_TRUE(devices_.scu()->snapshot().last_refusal.has_value());
  EXPECT_EQ(devices_.scu()->snapshot().last_refusal->command, scu::Command::execute) << "the F20 was refused";
  EXPECT_FALSE(emulated_.scu()->emergency_stop_active());
  // The next F20 goes out and holds.
  ASSERT_TRUE(cycle_until([&] { return emulated_.scu()->emergency_stop_active(); }, 500))
      << "the refused F20 was never sent again";
  EXPECT_TRUE(cycle_until([&] { return devices_.scu()->snapshot().emergency_stop_open; }, 50));
}

TEST_F(RefusedEmergencyStop, EveryAxisStillGetsAFastStopOfItsOwn) {
  start_x();
  // The SCU refuses every RE for a while: F20 does not hold, only the per-axis RS can stop x.
  emulated_.scu()->refuse_next_requests(1000, scu::Status::permission_error, scu::Command::execute);
  const double at_decision = emulated_.scu()->actuator(1).true_position_mm();
  halt_immediately();
  scu::RequestBytes fast_rs;
  ASSERT_TRUE(scu::encode_request(
      scu::StopRequest{static_cast<std::uint8_t>(cell_.axes[0].function - 1), scu::kFastStartStop}, fast_rs));
  scu_rec_.mark();
  bool fast_rs_sent = false;
  ASSERT_TRUE(cycle_until(
      [&] {
        fast_rs_sent = fast_rs_sent || scu_rec_.wrote_since_mark(fast_rs.view());
        return !emulated_.scu()->actuator(1).moving();
      },
      1000));
  EXPECT_FALSE(emulated_.scu()->emergency_stop_active());
  EXPECT_TRUE(fast_rs_sent) << "category 0 stops each axis fast (RS mode 0)";
  // Stopping distance, category 0: 10 mm/s for the time the RS waits behind the F20 (its reply and
  // refusal, two 38400-baud round trips, well under 50 ms: 0.5 mm) and no ramp. A soft stop would
  // add the 40 mm/s² ramp's 10²/(2·40) = 1.25 mm.
  const double travelled = emulated_.scu()->actuator(1).true_position_mm() - at_decision;
  EXPECT_LT(travelled, 0.5) << "stopped fast, not ramped down";
}

// Category 0 is the boundary's to enforce, whatever else the intents still say: an axis whose move is
// still asked for gets its fast stop all the same (here with F20 refused, so only that stop can act).
// Within 100 ms: the fast stop's round trips take well under 50 ms; without it the axis would run on
// until the SCU's own watchdog (0.5 s without a keep-alive, which the repeated F20s crowd out).
TEST_F(RefusedEmergencyStop, CategoryZeroStopsAnAxisWhoseMoveIsStillAskedFor) {
  start_x();
  emulated_.scu()->refuse_next_requests(1000, scu::Status::permission_error, scu::Command::execute);
  intents_.halt = cell::Halt::immediate;  // the move intent stays
  EXPECT_TRUE(cycle_until([&] { return !emulated_.scu()->actuator(1).moving(); }, 100))
      << "category 0 left the axis running because its intent still said move";
  EXPECT_FALSE(emulated_.scu()->watchdog_lapsed()) << "stopped by our stop, not by the SCU's watchdog";
}

TEST_F(Boundary, CategoryZeroStopsTheSpindleWhileItsRunIsStillAskedFor) {
  devices_.activate(clock_.now());
  ASSERT_TRUE(cycle_until([&] { return state_.links[1].active; }));
  intents_.spindle = {.run = true, .frequency_hz = 400.0, .clockwise = true, .reset = false};
  ASSERT_TRUE(cycle_until([&] { return state_.spindle.at_speed; }));
  intents_.halt = cell::Halt::immediate;  // the run intent stays
  EXPECT_TRUE(cycle_until([&] { return state_.spindle.at_rest; }, 5000))
      << "category 0 left the spindle turning because its intent still said run";
}

}  // namespace
}  // namespace cellctl::testing

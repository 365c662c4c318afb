// DpMaster against DpSlave over SimLink at 1.5 Mbaud 8E1 in virtual time: start-up to data
// exchange, refused parameters/configuration (more refusals in dp_startup_failures_test.cpp),
// watchdog, lost and returning slave, Set_Slave_Add, DH → diagnosis, FCB repetition, Global_Control.

#include <gtest/gtest.h>

#include <chrono>

#include "bus_fixture.hpp"
#include "profibus/fdl_codes.hpp"
#include "wire/hex.hpp"

namespace cellctl::profibus::testing {
namespace {

using std::chrono::milliseconds;

TEST(DpBus, PowerOnToDataExchange) {
  Bus bus;
  bus.master.activate(bus.now());
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::activating);
  const std::array<std::uint8_t, 4> out{0x01, 0x02, 0x03, 0x04};
  ASSERT_TRUE(bus.master.set_outputs(out));
  EXPECT_FALSE(bus.master.set_outputs(std::span<const std::uint8_t>(out).first(3))) << "wrong length";
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  // Start-up is a handful of request/reply pairs: well under 2 ms at 1.5 Mbaud.
  EXPECT_LT(bus.now() - link::TimePoint{}, milliseconds(2));
  EXPECT_EQ(bus.behaviour.entered, 1);
  EXPECT_EQ(bus.behaviour.last_user_prm, (std::vector<std::uint8_t>{0x00, 0x0c, 0x01}));
  const StandardDiag diag = bus.master.diagnosis().standard;
  EXPECT_TRUE(diag.ready_for_data_exchange());
  EXPECT_TRUE(diag.wd_on);
  EXPECT_EQ(diag.master_address, kMaster);
  EXPECT_EQ(diag.ident, kIdent);

  ASSERT_TRUE(bus.run_until([&] { return bus.master.stats().data_exchanges >= 10; }, milliseconds(20)));
  EXPECT_EQ(bus.behaviour.last_outputs, (std::vector<std::uint8_t>{1, 2, 3, 4}));
  EXPECT_EQ(bus.master.inputs().size(), 8u);
  EXPECT_EQ(bus.master.inputs()[0], static_cast<std::uint8_t>(bus.behaviour.exchanges));
  // 1 ms period on a fixed grid.
  EXPECT_NEAR(link::to_seconds(bus.master.stats().last_cycle), 1e-3, 1e-5);
  EXPECT_EQ(bus.master.health().timeouts, 0u);
  EXPECT_EQ(bus.master.health().bad_frames, 0u);
  EXPECT_LT(bus.master.input_age(bus.now()), milliseconds(2));
}

// A line kept busy by bytes that are no frame holds every request back (TSYN never passes), so no
// request goes unanswered: the master still leaves data exchange lost_slave_time after the last good
// reply, and names it.
TEST(DpBus, ALineBusyWithNoiseLosesTheSlaveAfterLostSlaveTime) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  bus.run_for(milliseconds(5));
  bus.slave.set_silent(true);
  const auto noise_from = bus.now();
  const std::vector<std::uint8_t> noise(250, 0x00);  // 250 octets: 1.8 ms of line at 1.5 Mbaud
  auto next_burst = bus.now();
  ASSERT_TRUE(bus.run_until(
      [&] {
        if (bus.now() >= next_burst) {
          (void)bus.sim.device().write(noise);
          next_burst = bus.now() + milliseconds(1);
        }
        return bus.master.lifecycle() != link::Lifecycle::active;
      },
      milliseconds(100)));
  EXPECT_LE(bus.now() - noise_from, milliseconds(22)) << "lost_slave_time 20 ms, checked every poll";
  EXPECT_EQ(bus.master.restart_reason(), "slave lost: no good reply within lost_slave_time");
  EXPECT_GT(bus.master.health().bad_frames, 0u);
}

TEST(DpBus, PrmVetoKeepsTheSlaveOutOfDataExchange) {
  Bus bus;
  bus.behaviour.veto = "units per revolution above the physical resolution";
  bus.master.activate(bus.now());
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  EXPECT_EQ(bus.master.dp_state(), DpState::refused);
  EXPECT_EQ(bus.master.last_startup_fault().kind, StartupFault::Kind::prm_fault);
  EXPECT_TRUE(bus.master.last_startup_fault().diagnosis.standard.prm_fault);
  EXPECT_TRUE(bus.master.last_startup_fault().diagnosis.standard.station_not_ready);
  EXPECT_EQ(bus.master.fault_reason(),
            "slave refused the parameters (Set_Prm): Prm_Fault; its diagnosis: Station_Not_Ready Prm_Fault "
            "Prm_Req, master none, ident 0x5C01");
  EXPECT_EQ(bus.slave.last_prm_reason(), "units per revolution above the physical resolution");
  // The profile can decode the extended diagnosis the slave sent with it.
  EXPECT_EQ(wire::to_hex(bus.master.last_startup_fault().diagnosis.extended.view()), "05 aa bb cc dd");
  bus.run_for(milliseconds(20));
  EXPECT_EQ(bus.behaviour.exchanges, 0);
  EXPECT_EQ(bus.slave.state(), DpSlaveState::wait_prm);
  EXPECT_EQ(bus.master.stats().data_exchanges, 0u);

  // Once the device accepts, activate() again brings it up.
  bus.behaviour.veto = {};
  bus.master.activate(bus.now());
  EXPECT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  EXPECT_TRUE(bus.slave.last_prm_reason().empty());
}

TEST(DpBus, CfgMismatchIsACfgFault) {
  auto setup = slave_setup();
  const std::array<std::uint8_t, 2> cfg{0x13, 0x23};  // 4 input octets instead of 8
  (void)setup.cfg.assign(cfg);
  Bus bus(master_config(), setup);
  bus.master.activate(bus.now());
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  EXPECT_EQ(bus.master.last_startup_fault().kind, StartupFault::Kind::cfg_fault);
  EXPECT_EQ(
      bus.master.fault_reason(),
      "slave refused the configuration (Chk_Cfg): Cfg_Fault; its diagnosis: Station_Not_Ready Cfg_Fault "
      "Prm_Req WD_On, master 2, ident 0x5C01");
  EXPECT_TRUE(bus.master.diagnosis().standard.cfg_fault);
  EXPECT_NE(bus.slave.state(), DpSlaveState::data_exchange);
  EXPECT_EQ(bus.behaviour.exchanges, 0);
}

TEST(DpBus, SilentMasterTripsTheSlaveWatchdog) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  bus.run_for(milliseconds(50));
  EXPECT_EQ(bus.behaviour.watchdog, 0) << "a master that talks keeps the watchdog fed";

  bus.master_running = false;
  const auto silent_from = bus.now();
  ASSERT_TRUE(
      bus.run_until([&] { return bus.slave.state() != DpSlaveState::data_exchange; }, milliseconds(200)));
  // 10 ms × 5 × 2 = 100 ms after the last request received: sent at most one 1 ms period before the
  // silence began, or still on the wire (one frame, < 200 µs) when it began.
  const auto after = bus.now() - silent_from;
  EXPECT_GE(after, milliseconds(99));
  EXPECT_LE(after, milliseconds(100) + std::chrono::microseconds(200));
  EXPECT_EQ(bus.behaviour.watchdog, 1);
  EXPECT_EQ(bus.behaviour.left, std::vector<LeaveReason>{LeaveReason::watchdog});
  EXPECT_EQ(bus.slave.standard_diag().master_address, kNoMaster);
  EXPECT_TRUE(bus.slave.standard_diag().prm_req);
}

TEST(DpBus, SilentSlaveIsDetectedAndRecovers) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  bus.run_for(milliseconds(5));

  bus.slave.set_silent(true);
  const auto silent_from = bus.now();
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() != link::Lifecycle::active; }, milliseconds(100)));
  // lost_slave_time (20 ms) from the last good reply, detected at the end of the next failed cycle.
  EXPECT_LE(bus.now() - silent_from, milliseconds(22));
  EXPECT_GE(bus.now() - silent_from, milliseconds(19));
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::activating);
  EXPECT_EQ(bus.master.stats().lost, 1u);
  EXPECT_EQ(bus.master.restart_reason(), "slave lost: no good reply within lost_slave_time");
  EXPECT_GT(bus.master.health().timeouts, 0u);
  EXPECT_GT(bus.master.health().retries, 0u);
  EXPECT_GE(bus.master.input_age(bus.now()), milliseconds(19));
  bus.run_for(milliseconds(30));
  EXPECT_NE(bus.master.lifecycle(), link::Lifecycle::active) << "nobody answers";

  bus.slave.set_silent(false);
  const auto back_at = bus.now();
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(20)));
  EXPECT_LE(bus.now() - back_at, milliseconds(7)) << "restart_delay 5 ms + start-up";
  const auto before = bus.master.stats().data_exchanges;
  bus.run_for(milliseconds(5));
  EXPECT_GE(bus.master.stats().data_exchanges, before + 4);
}

TEST(DpBus, SetSlaveAddressFrom126) {
  Bus bus(master_config(), slave_setup(kDefaultSlaveAddress), kDefaultSlaveAddress);
  bus.master.activate(bus.now());
  bus.run_for(milliseconds(5));
  EXPECT_EQ(bus.master.dp_state(), DpState::wait_address);
  EXPECT_EQ(bus.slave.counters().requests, 0u) << "nothing is sent to 126 unasked";
  EXPECT_FALSE(bus.master.set_slave_address(126, false)) << "126 is not a data-exchange address";

  ASSERT_TRUE(bus.master.set_slave_address(7, false));
  EXPECT_EQ(bus.master.address_change_status(), RequestStatus::pending);
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  EXPECT_EQ(bus.master.address_change_status(), RequestStatus::done);
  EXPECT_EQ(bus.slave.address(), 7);
  EXPECT_EQ(bus.master.station_address(), 7);
  EXPECT_EQ(bus.behaviour.new_address, std::optional<std::uint8_t>(7));
}

TEST(DpBus, SlaveAt126RefusesEverythingButSetSlaveAdd) {
  // A master configured for 126 cannot reach data exchange, and a slave there serves no Set_Prm.
  auto setup = slave_setup(kDefaultSlaveAddress);
  Bus bus(master_config(), setup, kDefaultSlaveAddress);
  link::SimLink& sim = bus.sim;
  const FdlFrame prm =
      make_sap_frame(126, kMaster, fc::kRequest | fc::kFcb | fc::kSrdHigh, sap::kSetPrm, sap::kMaster,
                     std::array<std::uint8_t, 7>{0x88, 1, 1, 11, 0x5c, 0x01, 0});
  std::array<std::uint8_t, kMaxFrameSize> out{};
  ASSERT_EQ(sim.master().write(std::span<const std::uint8_t>(out.data(), encode(prm, out))).count, 18u);
  FdlDecoder d;
  std::optional<FdlEvent> reply;
  for (int i = 0; i < 100 && !reply; ++i) {
    bus.slave.poll(bus.now());
    std::array<std::uint8_t, 64> buf{};
    const auto r = sim.master().read(buf);
    (void)d.push(std::span<const std::uint8_t>(buf.data(), r.count));
    reply = d.next();
    bus.clock.advance(std::chrono::microseconds(10));
  }
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->frame.fc, fc::kNotActivated);
  EXPECT_EQ(bus.slave.state(), DpSlaveState::wait_prm);
}

TEST(DpBus, DataHighMakesTheMasterReadTheDiagnosis) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  const auto reads = bus.master.stats().diag_reads;
  bus.behaviour.ext = {0x05, 0x01, 0x02, 0x03, 0x04};
  bus.behaviour.pending = true;
  EXPECT_TRUE(bus.slave.standard_diag().ext_diag);
  ASSERT_TRUE(bus.run_until([&] { return bus.master.stats().diag_reads > reads; }, milliseconds(5)));
  EXPECT_FALSE(bus.behaviour.pending) << "the master read it";
  EXPECT_TRUE(bus.master.diagnosis().standard.ext_diag);
  EXPECT_EQ(wire::to_hex(bus.master.diagnosis().extended.view()), "05 01 02 03 04");
  // Data exchange goes on without a restart.
  const auto cycles = bus.master.stats().data_exchanges;
  bus.run_for(milliseconds(5));
  EXPECT_GE(bus.master.stats().data_exchanges, cycles + 4);
  EXPECT_EQ(bus.master.stats().startups, 1u);
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::active);
}

TEST(DpBus, DeactivateClearsTheOutputs) {
  Bus bus;
  bus.master.activate(bus.now());
  const std::array<std::uint8_t, 4> out{9, 9, 9, 9};
  ASSERT_TRUE(bus.master.set_outputs(out));
  ASSERT_TRUE(bus.run_until([&] { return bus.master.stats().data_exchanges > 2; }, milliseconds(10)));
  bus.master.deactivate(bus.now());
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::deactivating);
  ASSERT_TRUE(bus.run_until([&] { return bus.behaviour.clears == 1; }, milliseconds(5)));
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::inactive);
  EXPECT_TRUE(std::ranges::all_of(bus.slave.outputs(), [](std::uint8_t b) { return b == 0; }));
}

TEST(DpBus, DeactivateFinishesEvenWhenTheSlaveIsSilent) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  bus.slave.set_silent(true);
  // Deactivate while a request is on the wire: its reply will never come.
  ASSERT_TRUE(bus.run_until([&] { return bus.sim.next_delivery().has_value(); }, milliseconds(2)));
  bus.master.deactivate(bus.now());
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() == link::Lifecycle::inactive; }, milliseconds(5)));
  EXPECT_EQ(bus.master.dp_state(), DpState::stopped);
  bus.run_for(milliseconds(5));
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::inactive) << "no restart after deactivate";
}

TEST(DpBus, FreezeHoldsTheInputsUntilUnfreeze) {
  auto setup = slave_setup();
  setup.freeze_req = true;
  Bus bus(master_config(), setup);
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  ASSERT_TRUE(bus.master.global_control(GlobalCommand::freeze));
  ASSERT_TRUE(bus.run_until([&] { return bus.slave.standard_diag().freeze_mode; }, milliseconds(5)));
  bus.run_for(milliseconds(2));
  const std::vector<std::uint8_t> frozen(bus.master.inputs().begin(), bus.master.inputs().end());
  bus.run_for(milliseconds(5));
  EXPECT_TRUE(std::ranges::equal(bus.master.inputs(), frozen)) << "inputs frozen";
  ASSERT_TRUE(bus.master.global_control(GlobalCommand::unfreeze));
  bus.run_for(milliseconds(3));
  EXPECT_FALSE(std::ranges::equal(bus.master.inputs(), frozen)) << "live again";
}

// Drops the next `drop` writes of the link it wraps: a reply lost on the line.
class LossyLink final : public link::Link {
 public:
  explicit LossyLink(link::Link& inner) : inner_(inner) {}
  link::IoResult read(std::span<std::uint8_t> b) override { return inner_.read(b); }
  link::IoResult write(std::span<const std::uint8_t> b) override {
    writes.emplace_back(b.begin(), b.end());
    if (drop > 0) {
      --drop;
      return {b.size()};
    }
    return inner_.write(b);
  }
  [[nodiscard]] std::string describe() const override { return "lossy"; }
  int drop = 0;
  std::vector<std::vector<std::uint8_t>> writes;

 private:
  link::Link& inner_;
};

TEST(DpBus, LostReplyIsRepeatedWithTheSameFcbAndNotReExecuted) {
  link::VirtualClock clock;
  link::SimLink sim(clock, link::line_8e1(1'500'000), "dp");
  LossyLink master_side(sim.master());
  LossyLink slave_side(sim.device());
  TestBehaviour behaviour;
  DpMaster master(master_side, master_config(), slave_setup());
  DpSlave slave(slave_side, DpSlaveConfig{kStation, kIdent}, behaviour);
  auto step = [&] {
    const auto t = clock.now();
    (void)master.poll(t);
    slave.poll(t);
    link::TimePoint next = t + milliseconds(1);
    for (auto d : {sim.next_delivery(), master.next_deadline(), slave.next_deadline()})
      if (d) next = std::min(next, *d);
    clock.advance_to(std::max(next, t + link::Duration{1}));
  };
  master.activate(clock.now());
  for (int i = 0; i < 2000 && master.stats().data_exchanges < 3; ++i) step();
  ASSERT_EQ(master.stats().data_exchanges, 3u);

  // The slave executes the next Data_Exchange, but its reply is lost.
  const int exchanges = behaviour.exchanges;
  const std::size_t master_writes = master_side.writes.size();
  slave_side.drop = 1;
  for (int i = 0; i < 2000 && master.stats().data_exchanges < 4; ++i) step();
  ASSERT_EQ(master.stats().data_exchanges, 4u);

  EXPECT_EQ(master.health().timeouts, 1u);
  EXPECT_EQ(master.health().retries, 1u);
  ASSERT_EQ(master_side.writes.size(), master_writes + 2);
  const auto& first = master_side.writes[master_writes];
  const auto& repeat = master_side.writes[master_writes + 1];
  EXPECT_EQ(repeat, first) << "same octets, hence the same FCB";
  EXPECT_NE(first[6] & fc::kFcv, 0) << "FCV set in data exchange";
  EXPECT_EQ(slave.counters().repeats, 1u);
  EXPECT_EQ(behaviour.exchanges, exchanges + 1) << "executed once, answered twice";
  ASSERT_GE(slave_side.writes.size(), 2u);
  EXPECT_EQ(slave_side.writes.back(), slave_side.writes[slave_side.writes.size() - 2])
      << "the previous reply";

  // The next cycle toggles the FCB and is executed normally.
  for (int i = 0; i < 2000 && master.stats().data_exchanges < 5; ++i) step();
  EXPECT_EQ(behaviour.exchanges, exchanges + 2);
  EXPECT_NE(master_side.writes.back()[6] & fc::kFcb, first[6] & fc::kFcb);
}

TEST(DpBus, FirstRequestsFollowTheFcbSequence) {
  link::VirtualClock clock;
  link::SimLink sim(clock, link::line_8e1(1'500'000), "dp");
  LossyLink master_side(sim.master());
  TestBehaviour behaviour;
  DpMaster master(master_side, master_config(), slave_setup());
  DpSlave slave(sim.device(), DpSlaveConfig{kStation, kIdent}, behaviour);
  master.activate(clock.now());
  for (int i = 0; i < 20000 && master.dp_state() != DpState::data_exchange; ++i) {
    (void)master.poll(clock.now());
    slave.poll(clock.now());
    clock.advance(std::chrono::microseconds(5));
  }
  ASSERT_GE(master_side.writes.size(), 5u);
  // FDL_Status, then Slave_Diag exactly as the notes' vector (master 2 → 5): FCB 1, FCV 0.
  EXPECT_EQ(wire::to_hex(master_side.writes[0]), "10 05 02 49 50 16");
  EXPECT_EQ(wire::to_hex(master_side.writes[1]), "68 05 05 68 85 82 6d 3c 3e ee 16");
  // Then Set_Prm with FCB 0 FCV 1, Chk_Cfg with FCB 1 FCV 1.
  EXPECT_EQ(master_side.writes[2][6], 0x5d);
  EXPECT_EQ(master_side.writes[3][6], 0x7d);
}

}  // namespace
}  // namespace cellctl::profibus::testing

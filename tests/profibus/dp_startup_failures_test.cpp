// DP start-up failures and replies that do not fit, each with who refused and why in the fault or
// restart reason: Set_Prm rejected (RS), Not_Supported, a slave locked by another master, a wrong
// ident, a malformed diagnosis, and Data_Exchange replies of the wrong length or with inputs the
// profile rejects. DpMaster against DpSlave, or against a scripted slave for replies a DpSlave never
// sends, over SimLink in virtual time.

#include <gtest/gtest.h>

#include <chrono>
#include <functional>

#include "bus_fixture.hpp"
#include "profibus/fdl_codes.hpp"

namespace cellctl::profibus::testing {
namespace {

using std::chrono::milliseconds;

bool has(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

// A slave that answers what `answer` says (nothing when it returns nullopt): for the replies a
// well-behaved DpSlave never gives.
struct ScriptedSlave {
  link::Link& link;
  std::function<std::optional<FdlFrame>(const FdlFrame&)> answer;
  FdlDecoder decoder;

  std::optional<link::TimePoint> poll() {
    std::array<std::uint8_t, 256> buf{};
    for (;;) {
      const auto r = link.read(buf);
      if (!r.ok() || r.count == 0) break;
      (void)decoder.push(std::span<const std::uint8_t>(buf.data(), r.count));
    }
    while (auto ev = decoder.next()) {
      if (ev->error != FdlError::none || !fc::is_request(ev->frame.fc)) continue;
      if (auto reply = answer(ev->frame)) {
        std::array<std::uint8_t, kMaxFrameSize> out{};
        (void)link.write(std::span<const std::uint8_t>(out.data(), encode(*reply, out)));
      }
    }
    return std::nullopt;  // answers at once
  }
};

// The replies of a fresh slave at kStation: FDL status, and a diagnosis awaiting parameters.
std::optional<FdlFrame> fresh_slave(const FdlFrame& request) {
  if (fc::function(request.fc) == fc::kFdlStatus) return make_frame(request.sa, kStation, fc::kOk);
  if (request.dsap == sap::kSlaveDiag) {
    StandardDiag d;
    d.station_not_ready = true;
    d.prm_req = true;
    d.ident = kIdent;
    std::array<std::uint8_t, kStandardDiagSize> bytes{};
    (void)encode(d, bytes);
    return make_sap_frame(request.sa, kStation, fc::kDataLow, sap::kMaster, sap::kSlaveDiag, bytes);
  }
  return std::nullopt;
}

// Steps a master against any slave on the bus's clock until pred() or `limit`; slave_poll returns
// the slave's next deadline.
using SlavePoll = std::function<std::optional<link::TimePoint>()>;
bool drive(Bus& bus, DpMaster& master, const SlavePoll& slave_poll, const std::function<bool()>& pred,
           link::Duration limit) {
  const auto deadline = bus.now() + limit;
  while (bus.now() < deadline) {
    if (pred()) return true;
    const auto t = bus.now();
    (void)master.poll(t);
    const auto slave_deadline = slave_poll();
    link::TimePoint next = t + milliseconds(1);
    for (auto d : {bus.sim.next_delivery(), master.next_deadline(), slave_deadline})
      if (d) next = std::min(next, *d);
    bus.clock.advance_to(std::max(next, t + link::Duration{1}));
  }
  return pred();
}

TEST(DpStartup, SetPrmAnsweredRsIsTheSlavesRefusal) {
  Bus bus;
  ScriptedSlave slave{bus.sim.device(),
                      [](const FdlFrame& req) -> std::optional<FdlFrame> {
                        if (req.dsap == sap::kSetPrm) return make_frame(req.sa, kStation, fc::kNotActivated);
                        return fresh_slave(req);
                      },
                      {}};
  bus.master.activate(bus.now());
  ASSERT_TRUE(drive(
      bus, bus.master, [&] { return slave.poll(); },
      [&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  const StartupFault& f = bus.master.last_startup_fault();
  EXPECT_EQ(f.kind, StartupFault::Kind::rejected);
  EXPECT_TRUE(f.by_slave());
  EXPECT_EQ(bus.master.dp_state(), DpState::refused);
  EXPECT_EQ(
      bus.master.fault_reason(),
      "slave rejected Set_Prm (RS: service not activated for master 2); its diagnosis: Station_Not_Ready "
      "Prm_Req, master none, ident 0x5C01");
  EXPECT_EQ(bus.master.health().error_replies, 1u);
}

TEST(DpStartup, FreezeRequestedOfASlaveWithoutFreezeIsNotSupported) {
  auto setup = slave_setup();
  setup.freeze_req = true;
  Bus bus(master_config(), setup);
  // The same bus, but this slave has no Freeze: built beside the fixture's (which is never polled).
  DpSlave plain(bus.sim.device(),
                DpSlaveConfig{kStation, kIdent, link::line_8e1(1'500'000), true, false, true}, bus.behaviour);
  bus.master.activate(bus.now());
  ASSERT_TRUE(drive(
      bus, bus.master,
      [&] {
        plain.poll(bus.now());
        return plain.next_deadline();
      },
      [&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  EXPECT_EQ(bus.master.last_startup_fault().kind, StartupFault::Kind::not_supported);
  EXPECT_TRUE(bus.master.last_startup_fault().diagnosis.standard.not_supported);
  EXPECT_EQ(plain.last_prm_reason(), "Freeze/Sync requested but not supported");
  EXPECT_TRUE(has(bus.master.fault_reason(),
                  "slave refused the parameters: a requested function (Freeze/Sync) "
                  "is Not_Supported; its diagnosis: Station_Not_Ready Not_Supported "
                  "Prm_Fault Prm_Req"))
      << bus.master.fault_reason();
  EXPECT_EQ(bus.behaviour.exchanges, 0);
}

// A slave whose diagnosis says it cannot exchange data yet (Stat_Diag) is asked again, not taken into
// data exchange; once it is ready the start-up completes. Not ready for longer than lost_slave_time
// (20 ms here) begins the start-up again with that reason.
TEST(DpStartup, ASlaveNotReadyYetIsNotTakenIntoDataExchange) {
  Bus bus;
  bus.behaviour.not_ready = true;
  bus.master.activate(bus.now());
  bus.run_for(milliseconds(15));
  EXPECT_NE(bus.master.lifecycle(), link::Lifecycle::active);
  EXPECT_NE(bus.master.dp_state(), DpState::data_exchange);
  EXPECT_EQ(bus.master.stats().data_exchanges, 0u);
  bus.behaviour.not_ready = false;
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(50)));

  Bus late;
  late.behaviour.not_ready = true;
  late.master.activate(late.now());
  ASSERT_TRUE(
      late.run_until([&] { return has(late.master.restart_reason(), "not ready"); }, milliseconds(100)))
      << late.master.restart_reason();
  EXPECT_EQ(late.master.stats().data_exchanges, 0u);
}

TEST(DpStartup, WrongIdentIsOurMastersRefusalNotTheSlaves) {
  auto setup = slave_setup();
  setup.ident = 0x0BAD;
  Bus bus(master_config(), setup);
  bus.master.activate(bus.now());
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  EXPECT_EQ(bus.master.last_startup_fault().kind, StartupFault::Kind::ident_mismatch);
  EXPECT_FALSE(bus.master.last_startup_fault().by_slave());
  EXPECT_EQ(bus.master.fault_reason(),
            "our master refused the slave: ident number 0x5C01, configured 0x0BAD; its diagnosis: "
            "Station_Not_Ready Prm_Req, master none, ident 0x5C01");
  EXPECT_TRUE(bus.behaviour.last_user_prm.empty()) << "no Set_Prm was sent";
}

TEST(DpStartup, SlaveLockedByAnotherMasterIsLeftAlone) {
  Bus bus;
  // Master 3 takes the slave first, with the watchdog off so that its lock outlives its silence.
  auto other_config = master_config();
  other_config.master_address = 3;
  other_config.wd_fact_1 = 0;
  DpMaster other(bus.sim.master(), other_config, slave_setup());
  other.activate(bus.now());
  ASSERT_TRUE(drive(
      bus, other,
      [&] {
        bus.slave.poll(bus.now());
        return bus.slave.next_deadline();
      },
      [&] { return other.lifecycle() == link::Lifecycle::active; }, milliseconds(10)));
  bus.run_for(milliseconds(1));  // master 3 falls silent; the slave stays locked to it

  bus.master.activate(bus.now());
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() == link::Lifecycle::fault; }, milliseconds(10)));
  const StartupFault& f = bus.master.last_startup_fault();
  EXPECT_EQ(f.kind, StartupFault::Kind::master_lock);
  EXPECT_FALSE(f.by_slave());
  EXPECT_TRUE(f.diagnosis.standard.master_lock) << "the master's own bit, set from the diagnosis";
  EXPECT_EQ(f.diagnosis.standard.master_address, 3);
  EXPECT_TRUE(has(bus.master.fault_reason(),
                  "our master refused to take the slave: it is locked by master 3 "
                  "(we are 2); its diagnosis: Master_Lock, master 3, ident 0x5C01"))
      << bus.master.fault_reason();
  EXPECT_EQ(bus.slave.state(), DpSlaveState::data_exchange) << "master 3's exchange is untouched";

  // A master that sends Set_Prm anyway is answered RS and changes nothing.
  std::array<std::uint8_t, 10> prm{};
  PrmStandard standard;
  standard.ident = kIdent;
  const std::size_t n = encode(standard, prm);
  const FdlFrame set_prm = make_sap_frame(kStation, kMaster, fc::kRequest | fc::kSrdHigh, sap::kSetPrm,
                                          sap::kMaster, std::span<const std::uint8_t>(prm.data(), n));
  std::array<std::uint8_t, kMaxFrameSize> out{};
  (void)bus.sim.master().write(std::span<const std::uint8_t>(out.data(), encode(set_prm, out)));
  FdlDecoder d;
  std::optional<FdlEvent> reply;
  for (int i = 0; i < 200 && !reply; ++i) {
    bus.slave.poll(bus.now());
    std::array<std::uint8_t, 64> buf{};
    const auto r = bus.sim.master().read(buf);
    (void)d.push(std::span<const std::uint8_t>(buf.data(), r.count));
    reply = d.next();
    bus.clock.advance(std::chrono::microseconds(10));
  }
  ASSERT_TRUE(reply);
  EXPECT_EQ(fc::function(reply->frame.fc), fc::kNotActivated);
  EXPECT_EQ(bus.slave.counters().locked_refusals, 1u);
  EXPECT_EQ(bus.slave.standard_diag().master_address, 3);
  EXPECT_EQ(bus.slave.state(), DpSlaveState::data_exchange);
}

TEST(DpStartup, MalformedDiagnosisIsCountedAndTheStartUpBegunAgain) {
  Bus bus;
  int diag_requests = 0;
  ScriptedSlave slave{bus.sim.device(),
                      [&](const FdlFrame& req) -> std::optional<FdlFrame> {
                        if (req.dsap == sap::kSlaveDiag) {
                          ++diag_requests;
                          const std::array<std::uint8_t, 3> cut{0x02, 0x05, 0x00};  // 3 of 6 standard octets
                          return make_sap_frame(req.sa, kStation, fc::kDataLow, sap::kMaster, sap::kSlaveDiag,
                                                cut);
                        }
                        return fresh_slave(req);
                      },
                      {}};
  bus.master.activate(bus.now());
  ASSERT_TRUE(drive(
      bus, bus.master, [&] { return slave.poll(); }, [&] { return diag_requests >= 3; }, milliseconds(100)));
  EXPECT_NE(bus.master.lifecycle(), link::Lifecycle::active);
  EXPECT_NE(bus.master.lifecycle(), link::Lifecycle::fault) << "a garbled reply is retried, not a refusal";
  EXPECT_EQ(bus.master.stats().diag_reads, 0u) << "nothing of it was taken as a diagnosis";
  EXPECT_GE(bus.master.stats().startups, 3u);
  EXPECT_GE(bus.master.health().error_replies, 2u);
  EXPECT_EQ(bus.master.restart_reason(),
            "Slave_Diag reply of 3 octets, 6 to 244 expected: not taken, start-up begun again");
}

TEST(DpStartup, DataExchangeReplyOfTheWrongLengthIsNotTakenAsInputs) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));
  bus.run_for(milliseconds(5));
  const std::vector<std::uint8_t> before(bus.master.inputs().begin(), bus.master.inputs().end());
  const auto good = bus.master.stats().data_exchanges;

  // The device now answers 6 octets where 8 are configured.
  bus.behaviour.input_length = 6;
  ASSERT_TRUE(
      bus.run_until([&] { return bus.master.lifecycle() != link::Lifecycle::active; }, milliseconds(3)));
  EXPECT_EQ(bus.master.lifecycle(), link::Lifecycle::activating) << "not active on replies it cannot use";
  EXPECT_EQ(bus.master.stats().bad_inputs, 1u);
  EXPECT_EQ(bus.master.stats().data_exchanges, good);
  EXPECT_EQ(std::vector<std::uint8_t>(bus.master.inputs().begin(), bus.master.inputs().end()), before)
      << "inputs not refreshed from a reply of the wrong shape";
  EXPECT_EQ(bus.master.restart_reason(),
            "Data_Exchange reply of 6 octets, 8 expected: not taken, start-up begun again");
  // While it persists: never active, the bad replies counted, the input age growing.
  bus.run_for(milliseconds(30));
  EXPECT_NE(bus.master.lifecycle(), link::Lifecycle::active);
  EXPECT_GE(bus.master.stats().bad_inputs, 2u);
  EXPECT_GE(bus.master.input_age(bus.now()), milliseconds(30));

  // Once the device answers in shape again, data exchange resumes.
  bus.behaviour.input_length = 8;
  EXPECT_TRUE(bus.run_until(
      [&] { return bus.in_data_exchange() && bus.master.stats().data_exchanges > good; }, milliseconds(20)));
}

TEST(DpStartup, InputsTheProfileRejectsAreCountedAndDoNotRefreshTheAge) {
  Bus bus;
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.master.stats().data_exchanges >= 3; }, milliseconds(10)));
  const auto exchanges = bus.master.stats().data_exchanges;
  bus.run_for(milliseconds(2));
  ASSERT_GT(bus.master.stats().data_exchanges, exchanges);
  const auto age_before = bus.master.input_age(bus.now());
  EXPECT_LT(age_before, milliseconds(1));
  bus.master.reject_input();
  EXPECT_EQ(bus.master.stats().bad_inputs, 1u);
  EXPECT_GE(bus.master.input_age(bus.now()), milliseconds(1))
      << "runs from the input before the rejected one";
}

}  // namespace
}  // namespace cellctl::profibus::testing

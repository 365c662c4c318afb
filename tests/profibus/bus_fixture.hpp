#pragma once
// A DP master and a DpSlave with a small test behaviour on one SimLink (1.5 Mbaud 8E1) in virtual
// time. The clock jumps from event to event (next octet on the wire, next master/slave deadline), so
// microsecond protocol timing is exact and the tests stay fast and deterministic.

#include <algorithm>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "link/sim_link.hpp"
#include "profibus/dp_master.hpp"
#include "profibus/dp_slave.hpp"

namespace cellctl::profibus::testing {

inline constexpr std::uint16_t kIdent = 0x5C01;
inline constexpr std::uint8_t kMaster = 2;
inline constexpr std::uint8_t kStation = 5;
// 8 input octets (0x17), 4 output octets (0x23): the encoder's Scancon 3.0 shape.
inline const std::vector<std::uint8_t> kCfg{0x17, 0x23};

// Counts what DpSlave asks of the device; inputs are a counter so every exchange is visible.
struct TestBehaviour final : SlaveBehaviour {
  std::string_view veto;  // non-empty: refuse Set_Prm with this reason
  std::vector<std::uint8_t> expected_cfg = kCfg;
  std::vector<std::uint8_t> last_user_prm;
  std::vector<std::uint8_t> last_outputs;
  std::vector<std::uint8_t> ext{0x05, 0xaa, 0xbb, 0xcc, 0xdd};
  bool pending = false;
  bool not_ready = false;        // Stat_Diag: the device cannot exchange data yet
  std::size_t input_length = 8;  // what exchange() answers: 8 is the configured length
  int exchanges = 0;
  int entered = 0;
  int watchdog = 0;
  int clears = 0;
  std::vector<LeaveReason> left;
  std::optional<std::uint8_t> new_address;

  PrmVerdict check_prm(std::span<const std::uint8_t> user_prm) override {
    last_user_prm.assign(user_prm.begin(), user_prm.end());
    return veto.empty() ? PrmVerdict{} : PrmVerdict{false, veto};
  }
  bool check_cfg(std::span<const std::uint8_t> cfg) override { return std::ranges::equal(cfg, expected_cfg); }
  std::size_t ext_diag(std::span<std::uint8_t> out) override {
    pending = false;  // read by the master
    std::ranges::copy(ext, out.begin());
    return ext.size();
  }
  std::size_t exchange(std::span<const std::uint8_t> outputs, std::span<std::uint8_t> inputs) override {
    last_outputs.assign(outputs.begin(), outputs.end());
    ++exchanges;
    for (std::size_t i = 0; i < input_length; ++i)
      inputs[i] = static_cast<std::uint8_t>(exchanges + static_cast<int>(i));
    return input_length;
  }
  bool diag_pending() override { return pending; }
  bool static_diag() override { return not_ready; }
  void on_data_exchange_entered() override { ++entered; }
  void on_data_exchange_left(LeaveReason r) override { left.push_back(r); }
  void on_watchdog_expired() override { ++watchdog; }
  void on_address_changed(std::uint8_t a, bool) override { new_address = a; }
  void on_clear_data() override { ++clears; }
};

inline DpMasterConfig master_config() {
  DpMasterConfig c;
  c.master_address = kMaster;
  c.wd_fact_1 = 5;  // 10 ms × 5 × 2 = 100 ms slave watchdog
  c.wd_fact_2 = 2;
  c.data_exchange_period = std::chrono::milliseconds(1);
  c.lost_slave_time = std::chrono::milliseconds(20);
  c.restart_delay = std::chrono::milliseconds(5);
  return c;
}

inline DpSlaveSetup slave_setup(std::uint8_t station = kStation) {
  DpSlaveSetup s;
  s.station_address = station;
  s.ident = kIdent;
  const std::array<std::uint8_t, 3> user{0x00, 0x0c, 0x01};
  (void)s.user_prm.assign(user);
  (void)s.cfg.assign(kCfg);
  s.input_length = 8;
  s.output_length = 4;
  return s;
}

struct Bus {
  explicit Bus(DpMasterConfig mc = master_config(), DpSlaveSetup setup = slave_setup(),
               std::uint8_t slave_address = kStation)
      : master(sim.master(), mc, setup),
        slave(sim.device(), DpSlaveConfig{slave_address, kIdent}, behaviour) {}

  link::VirtualClock clock;
  link::SimLink sim{clock, link::line_8e1(1'500'000), "dp"};
  TestBehaviour behaviour;
  DpMaster master;
  DpSlave slave;
  bool master_running = true;  // false: the master is silent (not polled)

  [[nodiscard]] link::TimePoint now() const { return clock.now(); }

  // Polls both ends at the current instant and jumps to the next event (at most 1 ms ahead).
  void step() {
    const auto t = clock.now();
    if (master_running) (void)master.poll(t);
    slave.poll(t);
    link::TimePoint next = t + std::chrono::milliseconds(1);
    for (auto d :
         {sim.next_delivery(), master_running ? master.next_deadline() : std::nullopt, slave.next_deadline()})
      if (d) next = std::min(next, *d);
    clock.advance_to(std::max(next, t + link::Duration{1}));
  }

  // Steps until pred() holds or `limit` of virtual time has passed; true when it held.
  bool run_until(const std::function<bool()>& pred, link::Duration limit) {
    const auto deadline = clock.now() + limit;
    while (clock.now() < deadline) {
      if (pred()) return true;
      step();
    }
    return pred();
  }
  void run_for(link::Duration span) {
    (void)run_until([] { return false; }, span);
  }

  bool in_data_exchange() const {
    return master.lifecycle() == link::Lifecycle::active && master.dp_state() == DpState::data_exchange &&
           slave.state() == DpSlaveState::data_exchange;
  }
};

}  // namespace cellctl::profibus::testing

// PROFIBUS DP-V0 Data_Exchange over SimLink at 1.5 Mbaud 8E1 in virtual time, with the encoder's
// Scancon 3.0 shape (4 output, 8 input octets), against the line limit of the protocol itself:
//
//   one cycle = TSYN (33 bit idle before the request) + request (SD2, 13 characters)
//             + min_TSDR (11 bit before the reply) + reply (SD3, 14 characters), 11 bits per character
//   (bench/dp_line_limit.hpp, shared with encoder_bench)
//
// ratio_vs_line = achieved cycles per virtual second / that limit (goal ≥ 0.9). The virtual clock
// jumps from event to event (sim.next_delivery(), the master's and slave's deadlines), so polling
// granularity does not enter. master_cpu_vs_wire = the master's CPU time per cycle (all its polls)
// / the cycle's wire time: how much of one core the master needs to keep the line busy.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>

#include "dp_line_limit.hpp"
#include "link/sim_link.hpp"
#include "profibus/dp_master.hpp"
#include "profibus/dp_slave.hpp"

namespace {

using namespace cellctl;
using namespace cellctl::profibus;

constexpr std::size_t kInputs = 8;
constexpr std::size_t kOutputs = 4;

// An encoder-shaped device: 8 input octets that change every cycle.
struct CountingDevice final : SlaveBehaviour {
  std::uint32_t count = 0;
  PrmVerdict check_prm(std::span<const std::uint8_t>) override { return {}; }
  bool check_cfg(std::span<const std::uint8_t>) override { return true; }
  std::size_t ext_diag(std::span<std::uint8_t>) override { return 0; }
  std::size_t exchange(std::span<const std::uint8_t>, std::span<std::uint8_t> inputs) override {
    ++count;
    for (std::size_t i = 0; i < kInputs; ++i) inputs[i] = static_cast<std::uint8_t>(count >> (i % 4 * 8));
    return kInputs;
  }
};

void BM_DataExchangeOverSimLink(benchmark::State& state) {
  link::VirtualClock clock;
  const auto line = link::line_8e1(1'500'000);
  link::SimLink sim(clock, line, "bench");
  DpMasterConfig config;
  config.master_address = 2;
  config.data_exchange_period = link::Duration{0};  // back to back: the line is the limit
  DpSlaveSetup setup;
  setup.station_address = 5;
  setup.ident = 0x5C01;
  const std::array<std::uint8_t, 2> cfg{0x17, 0x23};
  (void)setup.cfg.assign(cfg);
  setup.input_length = kInputs;
  setup.output_length = kOutputs;
  CountingDevice device;
  DpMaster master(sim.master(), config, setup);
  DpSlave slave(sim.device(), DpSlaveConfig{5, 0x5C01, line}, device);

  link::Duration master_cpu{};
  auto step = [&] {
    const auto t = clock.now();
    const auto c0 = std::chrono::steady_clock::now();
    (void)master.poll(t);
    master_cpu += std::chrono::steady_clock::now() - c0;
    slave.poll(t);
    link::TimePoint next = t + std::chrono::milliseconds(1);
    for (auto d : {sim.next_delivery(), master.next_deadline(), slave.next_deadline()})
      if (d) next = std::min(next, *d);
    clock.advance_to(std::max(next, t + link::Duration{1}));
  };
  master.activate(clock.now());
  while (master.stats().data_exchanges < 2) step();

  const auto cycles0 = master.stats().data_exchanges;
  const auto t0 = clock.now();
  master_cpu = {};
  for (auto _ : state) {
    const auto target = master.stats().data_exchanges + 1;
    while (master.stats().data_exchanges < target) step();
  }
  const double cycles = static_cast<double>(master.stats().data_exchanges - cycles0);
  const double virtual_s = link::to_seconds(clock.now() - t0);
  if (master.health().timeouts != 0 || master.lifecycle() != link::Lifecycle::active)
    state.SkipWithError("the exchange did not run cleanly");

  const double wire_s = bench::dx_cycle_wire_s(line, config.min_tsdr_bits, kOutputs, kInputs);
  const double rate = cycles / virtual_s;
  state.counters["cycles_per_virtual_s"] = rate;
  state.counters["line_limit_per_s"] = 1.0 / wire_s;
  state.counters["ratio_vs_line"] = rate * wire_s;
  state.counters["request_chars"] = static_cast<double>(bench::dx_frame_chars(kOutputs));
  state.counters["reply_chars"] = static_cast<double>(bench::dx_frame_chars(kInputs));
  const double cpu_per_cycle = link::to_seconds(master_cpu) / cycles;
  state.counters["master_cpu_us_per_cycle"] = cpu_per_cycle * 1e6;
  state.counters["master_cpu_vs_wire"] = cpu_per_cycle / wire_s;
}
BENCHMARK(BM_DataExchangeOverSimLink);

}  // namespace

BENCHMARK_MAIN();

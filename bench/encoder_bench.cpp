// The encoder at the device level: encoder::Session (DP master) against encoder::Emulator (the
// SCH88BEX as DP slave, its shaft turning with a moving axis) over SimLink at 1.5 Mbaud 8E1 in virtual
// time, functionality Scancon 3.0 (4 output, 8 input octets), Data_Exchange back to back.
//
// The reference is the protocol's own line limit (bench/dp_line_limit.hpp, the same formula as
// profibus_bench): TSYN + request + min_TSDR + reply, at 11 bits per character.
//   ratio_vs_line      = achieved Data_Exchange cycles per virtual second / that limit (goal ≥ 0.9)
//   master_cpu_vs_wire = the session's CPU time per cycle (all its polls, typed decoding included) /
//                        the cycle's wire time: the share of one core the master needs to keep the
//                        line busy.
// The virtual clock jumps from event to event (sim.next_delivery(), the session's and the emulator's
// deadlines), so polling granularity does not enter the rate.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dp_line_limit.hpp"
#include "encoder/emulator.hpp"
#include "encoder/session.hpp"
#include "link/sim_link.hpp"
#include "plant/shaft.hpp"

namespace {

using namespace cellctl;

constexpr std::uint8_t kStation = 5;
constexpr double kMmPerRevolution = 4.0;
constexpr double kAxisSpeedMmS = 20.0;  // the shaft turns, so every reply carries a new position
const encoder::PhysicalResolution kPhysical{8192, 4096};

void BM_EncoderDataExchangeOverSimLink(benchmark::State& state) {
  link::VirtualClock clock;
  const auto line = link::line_8e1(1'500'000);
  link::SimLink sim(clock, line, "encoder");
  const auto start = clock.now();
  const plant::Shaft shaft(plant::ShaftParams{kMmPerRevolution, 0.0, 0.0},
                           [&] { return kAxisSpeedMmS * link::to_seconds(clock.now() - start); });

  encoder::EmulatorConfig emu_config;
  emu_config.address = kStation;
  emu_config.identity.physical = kPhysical;
  emu_config.line = line;
  encoder::Emulator emulator(sim.device(), emu_config, shaft);

  encoder::SessionConfig config;
  config.station_address = kStation;
  config.parameters.functionality = encoder::Functionality::scancon30;
  config.physical = kPhysical;
  config.mm_per_revolution = kMmPerRevolution;
  config.bus.master_address = 2;
  config.bus.line = line;
  config.bus.data_exchange_period = link::Duration{0};  // back to back: the line is the limit
  encoder::Session session(sim.master(), config);

  link::Duration master_cpu{};
  link::Lifecycle lifecycle = link::Lifecycle::inactive;
  auto step = [&] {
    const auto t = clock.now();
    const auto c0 = std::chrono::steady_clock::now();
    session.receive(t);
    session.transmit(t);
    lifecycle = session.lifecycle();
    master_cpu += std::chrono::steady_clock::now() - c0;
    emulator.poll(t);
    link::TimePoint next = t + std::chrono::milliseconds(1);
    for (auto d : {sim.next_delivery(), session.next_deadline(), emulator.next_deadline()})
      if (d) next = std::min(next, *d);
    clock.advance_to(std::max(next, t + link::Duration{1}));
  };
  session.activate(clock.now());
  const auto startup_limit = clock.now() + std::chrono::seconds(1);
  while (session.snapshot().exchanges < 2 && lifecycle != link::Lifecycle::fault &&
         clock.now() < startup_limit)
    step();
  if (session.snapshot().exchanges < 2) {
    state.SkipWithError("the encoder did not reach data exchange");
    for (auto _ : state) {
    }
    return;
  }

  const auto cycles0 = session.snapshot().exchanges;
  const auto timeouts0 = session.health().timeouts;
  const auto t0 = clock.now();
  master_cpu = {};
  for (auto _ : state) {
    const auto target = session.snapshot().exchanges + 1;
    while (session.snapshot().exchanges < target && lifecycle != link::Lifecycle::fault) step();
  }
  const double cycles = static_cast<double>(session.snapshot().exchanges - cycles0);
  const double virtual_s = link::to_seconds(clock.now() - t0);
  // The figures only count if every cycle was a good one and the position is the shaft's.
  const double true_mm = kAxisSpeedMmS * link::to_seconds(clock.now() - start);
  if (lifecycle != link::Lifecycle::active || session.health().timeouts != timeouts0 || cycles < 1.0 ||
      std::abs(session.snapshot().position_mm - true_mm) > 0.05)
    state.SkipWithError("the exchange did not run cleanly");

  const double wire_s = bench::dx_cycle_wire_s(line, config.bus.min_tsdr_bits,
                                               encoder::output_length(config.parameters.functionality),
                                               encoder::input_length(config.parameters.functionality));
  const double rate = cycles / virtual_s;
  state.counters["cycles_per_virtual_s"] = rate;
  state.counters["line_limit_per_s"] = 1.0 / wire_s;
  state.counters["ratio_vs_line"] = rate * wire_s;
  const double cpu_per_cycle = link::to_seconds(master_cpu) / cycles;
  state.counters["master_cpu_us_per_cycle"] = cpu_per_cycle * 1e6;
  state.counters["master_cpu_vs_wire"] = cpu_per_cycle / wire_s;
}
BENCHMARK(BM_EncoderDataExchangeOverSimLink);

}  // namespace

BENCHMARK_MAIN();

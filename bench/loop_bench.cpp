// The control loop in real time: wake-up jitter at 1 kHz, compute time per stage of a representative
// body (a 6-axis planner step in the supervisor stage), and heap allocations per cycle after start.
// Ratios against the same run's reference: p99 jitter / period, busy time / elapsed time, allocations
// / cycles. One long iteration; the duration is an option so it can run short:
//
//   loop_bench --duration_s=30 [--period_us=1000] [--fifo=80] [--mlock] [--cpu=1]
//
// Real-time set-up is attempted only when asked and reported either way (refusal is not fatal).

#include <benchmark/benchmark.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <string_view>

#include "link/clock.hpp"
#include "loop/loop.hpp"
#include "loop/realtime_setup.hpp"
#include "planner/planner.hpp"
#include "support/allocation_counter.hpp"

namespace {

using namespace cellctl;
using namespace std::chrono_literals;

struct Options {
  double duration_s = 30.0;
  std::int64_t period_us = 1000;
  loop::RealtimeConfig realtime;
};

Options g_options;

// Takes the options Google Benchmark did not consume; unknown ones are an error.
bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&](std::string_view key) -> const char* {
      return a.substr(0, key.size()) == key ? argv[i] + key.size() : nullptr;
    };
    if (const char* v = value("--duration_s=")) {
      o.duration_s = std::atof(v);
    } else if (const char* p = value("--period_us=")) {
      o.period_us = std::atoll(p);
    } else if (const char* f = value("--fifo=")) {
      o.realtime.fifo_priority = std::atoi(f);
    } else if (const char* c = value("--cpu=")) {
      o.realtime.cpu = std::atoi(c);
    } else if (a == "--mlock") {
      o.realtime.lock_memory = true;
    } else {
      std::fprintf(stderr, "loop_bench: unknown option %s\n", argv[i]);
      return false;
    }
  }
  return o.duration_s > 0.0 && o.period_us > 0;
}

// A stand-in for the cell's cycle: bytes in, a snapshot, limit checks, a planner step, bytes out.
struct DummyCell {
  planner::Planner<6> planner{1e-3};
  planner::Input<6> input;
  planner::Output<6> output;
  std::array<std::uint8_t, 64> rx{};
  std::array<std::uint8_t, 64> tx{};
  std::array<double, 6> snapshot{};
  std::uint32_t checksum = 0;
  int faults = 0;

  DummyCell() {
    input.max_velocity.setConstant(50.0);
    input.max_acceleration.setConstant(500.0);
    input.max_jerk.setConstant(5000.0);
  }

  void read_sessions(std::uint64_t cycle) {
    for (std::size_t i = 0; i < rx.size(); ++i) rx[i] = static_cast<std::uint8_t>(cycle + i);
    checksum = std::accumulate(rx.begin(), rx.end(), checksum,
                               [](std::uint32_t s, std::uint8_t b) { return (s << 5) ^ (s >> 27) ^ b; });
  }
  void state() {
    for (int i = 0; i < 6; ++i) snapshot[static_cast<std::size_t>(i)] = output.new_position[i];
  }
  void monitor() {
    for (const double p : snapshot) faults += std::abs(p) > 1e3 ? 1 : 0;
  }
  void supervisor(std::uint64_t cycle) {
    if (cycle % 2000 == 0) input.target_position.setConstant(cycle % 4000 == 0 ? 100.0 : -100.0);
    if (!planner::is_error(planner.update(input, output))) output.pass_to_input(input);
  }
  void write_sessions() {
    for (std::size_t i = 0; i < 6; ++i) {
      const auto counts = static_cast<std::int32_t>(snapshot[i] * 1000.0);
      std::memcpy(&tx[i * 4], &counts, sizeof(counts));
    }
    benchmark::DoNotOptimize(tx);
  }
};

void BM_LoopWakeUpJitter(benchmark::State& state) {
  const loop::RealtimeReport rt = loop::apply_realtime(g_options.realtime);
  std::printf("%s\n", rt.summary().c_str());
  for (const auto& w : rt.warnings()) std::printf("warning: %s\n", w.c_str());

  link::MonotonicClock clock;
  loop::MonotonicWaiter waiter;
  const link::Duration period = std::chrono::microseconds{g_options.period_us};
  loop::Loop cycle(clock, waiter, period);
  DummyCell cell;
  std::atomic<bool> stop{false};
  const auto cycles = static_cast<std::uint64_t>(
      std::llround(g_options.duration_s * 1e6 / static_cast<double>(g_options.period_us)));
  using loop::ControlStage;
  using loop::index;
  std::size_t allocations = 0;
  link::Duration elapsed{};
  for (auto _ : state) {
    const link::TimePoint start = clock.now();
    const std::size_t before = testing::allocation_count();
    cycle.run(
        [&](link::TimePoint, std::uint64_t n) {
          {
            const auto t = cycle.time_stage(index(ControlStage::read_sessions));
            cell.read_sessions(n);
          }
          {
            const auto t = cycle.time_stage(index(ControlStage::state));
            cell.state();
          }
          {
            const auto t = cycle.time_stage(index(ControlStage::monitor));
            cell.monitor();
          }
          {
            const auto t = cycle.time_stage(index(ControlStage::supervisor));
            cell.supervisor(n);
          }
          {
            const auto t = cycle.time_stage(index(ControlStage::write_sessions));
            cell.write_sessions();
          }
        },
        stop, cycles);
    allocations = testing::allocation_count() - before;
    elapsed = clock.now() - start;
  }
  benchmark::DoNotOptimize(cell.checksum);

  const loop::LoopStats& s = cycle.stats();
  const auto us = [](link::Duration d) { return std::chrono::duration<double, std::micro>(d).count(); };
  const double period_us = us(period);
  state.counters["cycles"] = static_cast<double>(s.cycles);
  state.counters["jitter_p50_us"] = us(s.jitter.percentile(0.5));
  state.counters["jitter_p99_us"] = us(s.jitter.percentile(0.99));
  state.counters["jitter_p999_us"] = us(s.jitter.percentile(0.999));
  state.counters["jitter_max_us"] = us(s.jitter.max());
  state.counters["p99_jitter_per_period"] = us(s.jitter.percentile(0.99)) / period_us;
  state.counters["missed_per_cycle"] =
      static_cast<double>(s.missed_deadlines) / static_cast<double>(s.cycles);
  state.counters["allocs_per_cycle"] = static_cast<double>(allocations) / static_cast<double>(s.cycles);
  link::Duration busy{};
  for (std::size_t i = 0; i < cycle.stages().size(); ++i) busy += cycle.stages().histogram(i).total();
  state.counters["busy_per_elapsed"] = us(busy) / us(elapsed);
  state.counters["supervisor_mean_us"] = us(cycle.stages().histogram(index(ControlStage::supervisor)).mean());
  std::printf("%s", cycle.summary().c_str());
  std::printf("heap allocations after start: %zu over %llu cycles\n", allocations,
              static_cast<unsigned long long>(s.cycles));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!parse(argc, argv, g_options)) return 2;
  benchmark::RegisterBenchmark("BM_LoopWakeUpJitter", BM_LoopWakeUpJitter)
      ->Iterations(1)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

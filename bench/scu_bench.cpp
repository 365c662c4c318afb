// SCU benchmarks, each reported as a ratio against a reference computed in the same run:
//  - all-actuator state refresh: RC round trips per second achieved by scu::Session against
//    scu::Emulator over a SimLink at 38400 8N1 (keep-alive back to back), over the limit the line
//    allows for those telegram lengths (goal ≥ 0.9);
//  - codec: encode+decode of an RC request and its cyclic reply per second, over the rate at which the
//    line can carry them (how much CPU headroom the codec leaves).

#include <benchmark/benchmark.h>

#include <chrono>

#include "link/sim_link.hpp"
#include "scu/emulator.hpp"
#include "scu/session.hpp"

namespace {

using namespace cellctl;
using namespace std::chrono_literals;

constexpr std::size_t kRcRequestBytes = 7;  // R C ctp ctp index crc crc

scu::SessionConfig back_to_back(int actuators) {
  scu::SessionConfig c;
  c.actuators = 0;
  for (int a = 0; a < actuators; ++a) c.actuators.set(static_cast<std::size_t>(a));
  c.functions = scu::scp11(c.actuators);
  c.keepalive_period = link::Duration::zero();
  return c;
}

void BM_AllActuatorRefreshRate(benchmark::State& state) {
  const int actuators = static_cast<int>(state.range(0));
  const auto format = link::line_8n1(38400);
  double achieved = 0.0, limit = 0.0;
  for (auto _ : state) {
    link::VirtualClock clock;
    link::SimLink sim(clock, format, "scu");
    scu::Emulator emulator(sim.device(), scu::scp11_emulator(actuators, plant::ActuatorParams{}, 100.0));
    scu::Session session(sim.master(), back_to_back(actuators));
    const auto step = [&] {
      emulator.poll(clock.now());
      session.receive(clock.now());
      session.transmit(clock.now());
      // Jump to the next byte on the wire; a small step when the line is idle.
      clock.advance_to(sim.next_delivery().value_or(clock.now() + 50us));
    };
    session.activate(clock.now());
    while (session.lifecycle() != link::Lifecycle::active) step();
    const auto start = clock.now();
    const auto first = session.snapshot().refreshes;
    while (clock.now() - start < 10s) step();
    const auto span = link::to_seconds(clock.now() - start);
    achieved = static_cast<double>(session.snapshot().refreshes - first) / span;
    const std::size_t reply = 5 + 2 + session.layout().read_size();  // R C ACK crc crc + ctp + read data
    limit = 1.0 / (static_cast<double>((kRcRequestBytes + reply) * format.bits_per_char()) / format.baud);
  }
  state.counters["refresh_per_s"] = achieved;
  state.counters["line_limit_per_s"] = limit;
  state.counters["ratio_to_line_limit"] = achieved / limit;
}
BENCHMARK(BM_AllActuatorRefreshRate)->Arg(1)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);

void BM_CodecRoundTrip(benchmark::State& state) {
  const scu::CyclicLayout layout(0b111111);
  std::array<std::uint8_t, 64> data{};
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 37);
  const auto read = std::span(data).first(layout.read_size());
  scu::RequestBytes request;
  scu::ReplyBytes reply;
  scu::CyclicRefresh refresh;
  std::size_t bytes = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    const scu::CyclicRequest rc{0, {}};
    benchmark::DoNotOptimize(scu::encode_request(rc, request));
    const auto req = scu::decode_request(request.view());
    benchmark::DoNotOptimize(req.error);
    benchmark::DoNotOptimize(
        scu::encode_reply(scu::Reply{scu::Command::cyclic, scu::Status::ack, true, read}, reply));
    const auto rep = scu::decode_reply(reply.view(), scu::reply_shape(rc));
    benchmark::DoNotOptimize(layout.decode(rep.value.data, refresh));
    bytes = request.size() + reply.size();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto format = link::line_8n1(38400);
  const double line_pairs_per_s = format.baud / static_cast<double>(format.bits_per_char() * bytes);
  const double pairs_per_s = static_cast<double>(state.iterations()) / seconds;
  state.counters["pairs_per_s"] = pairs_per_s;
  state.counters["line_pairs_per_s"] = line_pairs_per_s;
  state.counters["ratio_to_line"] = pairs_per_s / line_pairs_per_s;
}
BENCHMARK(BM_CodecRoundTrip);

}  // namespace

BENCHMARK_MAIN();

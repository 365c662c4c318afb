// spindle::Codec throughput against the line it serves: telegrams decoded (and encoded) per second
// divided by the telegrams per second a 38400 8N1 line can carry. A ratio far above 1 means the codec
// is never what limits the spindle link.

#include <benchmark/benchmark.h>

#include <array>
#include <chrono>

#include "link/line_format.hpp"
#include "spindle/codec.hpp"

namespace {

using namespace cellctl;

// Telegrams per second the line carries for frames of `frame_length` characters.
double line_telegrams_per_s(std::size_t frame_length) {
  const auto line = link::line_8n1(38400);
  return static_cast<double>(line.baud) / line.bits_per_char() / static_cast<double>(frame_length);
}

// Rate and dimensionless ratio to the line, from the loop's own wall time (a kIsRate counter would
// label the ratio "/s").
void report(benchmark::State& state, double telegrams, std::chrono::steady_clock::duration elapsed,
            std::size_t frame_length) {
  const double rate = telegrams / std::chrono::duration<double>(elapsed).count();
  state.counters["telegrams_per_s"] = rate;
  state.counters["line_telegrams_per_s"] = line_telegrams_per_s(frame_length);
  state.counters["ratio_vs_line"] = rate / line_telegrams_per_s(frame_length);
}

// The longest telegram (RES 0x59, 64 characters): the worst case for the decoder.
spindle::StatusValues sample_values() {
  return {400, 800, 399, 2000, 4800, 100, 180, 1, 269, 6};
}

void BM_DecodeStatusResponse(benchmark::State& state) {
  std::array<std::uint8_t, spindle::kMaxFrameLength> frame{};
  const std::size_t n = spindle::Codec::encode(sample_values(), frame);
  spindle::FrameDecoder decoder;
  std::int64_t decoded = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      auto d = decoder.push(frame[i]);
      benchmark::DoNotOptimize(d);
      if (d && d->ok()) ++decoded;
    }
  }
  const auto elapsed = std::chrono::steady_clock::now() - t0;
  if (decoded != state.iterations()) state.SkipWithError("a telegram failed to decode");
  report(state, static_cast<double>(decoded), elapsed, n);
}
BENCHMARK(BM_DecodeStatusResponse);

void BM_EncodeStatusResponse(benchmark::State& state) {
  std::array<std::uint8_t, spindle::kMaxFrameLength> frame{};
  const spindle::Message message = sample_values();
  std::size_t n = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    n = spindle::Codec::encode(message, frame);
    benchmark::DoNotOptimize(frame);
  }
  report(state, static_cast<double>(state.iterations()), std::chrono::steady_clock::now() - t0, n);
}
BENCHMARK(BM_EncodeStatusResponse);

}  // namespace

BENCHMARK_MAIN();

#pragma once
// How fast the core runs code that needs many instructions per cycle, right now: a loop of eight
// independent multiply-adds and four integer operations per iteration (about four instructions per
// cycle), in registers only; its time in milliseconds, best of three. On the 2-core VM the planner's
// times swing by 1.2–1.8x between a fast and a slow state of the machine, within one process; this
// loop swings with them, a latency-bound one does not (docs/measurements.md, session 18: a core
// shared with a co-runner, most likely). planner_bench prints it beside each figure, so that a run
// can be told to be in one state or the other.

#include <algorithm>
#include <chrono>
#include <cstdint>

namespace cellctl::bench {

inline double core_probe_ms() noexcept {
  volatile int iterations = 2'000'000;  // read at run time: the loop is not folded away
  volatile double sink = 0.0;
  double best = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    const auto t0 = std::chrono::steady_clock::now();
    double x0 = 1.0, x1 = 2.0, x2 = 3.0, x3 = 4.0, x4 = 5.0, x5 = 6.0, x6 = 7.0, x7 = 8.0;
    std::uint64_t i0 = 1, i1 = 2, i2 = 3, i3 = 4;
    const int n = iterations;
    for (int it = 0; it < n; ++it) {
      x0 = x0 * 0.9999999 + 1e-7;
      x1 = x1 * 0.9999999 + 1e-7;
      x2 = x2 * 0.9999999 + 1e-7;
      x3 = x3 * 0.9999999 + 1e-7;
      x4 = x4 * 0.9999999 + 1e-7;
      x5 = x5 * 0.9999999 + 1e-7;
      x6 = x6 * 0.9999999 + 1e-7;
      x7 = x7 * 0.9999999 + 1e-7;
      i0 = i0 * 3 + static_cast<std::uint64_t>(it);
      i1 ^= i0 >> 3U;
      i2 += i1 & 7U;
      i3 = (i3 << 1U) ^ i2;
    }
    const auto t1 = std::chrono::steady_clock::now();
    sink = x0 + x1 + x2 + x3 + x4 + x5 + x6 + x7 + static_cast<double>(i0 ^ i1 ^ i2 ^ i3);
    best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  static_cast<void>(sink);
  return best;
}

}  // namespace cellctl::bench

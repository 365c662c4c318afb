#pragma once
// A fixed-size histogram of durations with log-spaced bins from 100 ns to 100 ms (20 per decade, so
// a bin is 12 % wide), plus an underflow bin [0, 100 ns) and an overflow bin [100 ms, inf). The range
// starts below 1 us because stage compute times are often sub-microsecond. Recording
// is a binary search in a constant table: no allocation, safe inside the control cycle.

#include <array>
#include <cstddef>
#include <cstdint>

#include "link/clock.hpp"

namespace cellctl::loop {

class LatencyHistogram {
 public:
  static constexpr std::size_t kBinsPerDecade = 20;
  static constexpr std::size_t kDecades = 6;  // 100 ns .. 100 ms
  static constexpr std::size_t kLogBins = kBinsPerDecade * kDecades;
  static constexpr std::size_t kBins = kLogBins + 2;  // + underflow + overflow

  // Negative durations (a clock that woke before its deadline) count as zero.
  void record(link::Duration d) noexcept;

  [[nodiscard]] std::uint64_t count() const noexcept { return count_; }
  [[nodiscard]] link::Duration max() const noexcept { return max_; }
  [[nodiscard]] link::Duration total() const noexcept { return total_; }
  [[nodiscard]] link::Duration mean() const noexcept;
  [[nodiscard]] std::uint64_t bin_count(std::size_t bin) const noexcept { return bins_[bin]; }

  // The q-quantile (0 < q <= 1) as the upper edge of the bin that holds it, capped at max(): never
  // under-reported, at most one bin (12 %) over. Zero when nothing was recorded.
  [[nodiscard]] link::Duration percentile(double q) const noexcept;

  // Bin b holds [lower_edge(b), upper_edge(b)); the overflow bin's upper edge is Duration::max().
  [[nodiscard]] static link::Duration lower_edge(std::size_t bin) noexcept;
  [[nodiscard]] static link::Duration upper_edge(std::size_t bin) noexcept;
  [[nodiscard]] static std::size_t bin_of(link::Duration d) noexcept;

 private:
  std::array<std::uint64_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  link::Duration max_{0};
  link::Duration total_{0};
};

}  // namespace cellctl::loop

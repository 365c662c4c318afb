#include "loop/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace cellctl::loop {
namespace {

using link::Duration;

// edges[k] = 100 ns * 10^(k / 20) for k = 0 .. kLogBins, rounded to whole nanoseconds (so the decade
// edges are exact: 100 ns, 1 us, 10 us, ...).
const std::array<std::int64_t, LatencyHistogram::kLogBins + 1>& edges() noexcept {
  static const auto table = [] {
    std::array<std::int64_t, LatencyHistogram::kLogBins + 1> t{};
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double exponent = static_cast<double>(k) / static_cast<double>(LatencyHistogram::kBinsPerDecade);
      t[k] = std::llround(100.0 * std::pow(10.0, exponent));
    }
    return t;
  }();
  return table;
}

}  // namespace

std::size_t LatencyHistogram::bin_of(Duration d) noexcept {
  const auto& e = edges();
  // upper_bound: the first edge above d; d below edges[0] -> 0 (underflow), above the last -> overflow.
  return static_cast<std::size_t>(std::upper_bound(e.begin(), e.end(), d.count()) - e.begin());
}

Duration LatencyHistogram::lower_edge(std::size_t bin) noexcept {
  return bin == 0 ? Duration{0} : Duration{edges()[std::min(bin, kLogBins + 1) - 1]};
}

Duration LatencyHistogram::upper_edge(std::size_t bin) noexcept {
  return bin > kLogBins ? Duration::max() : Duration{edges()[bin]};
}

void LatencyHistogram::record(Duration d) noexcept {
  if (d < Duration{0}) d = Duration{0};
  ++bins_[bin_of(d)];
  ++count_;
  total_ += d;
  max_ = std::max(max_, d);
}

Duration LatencyHistogram::mean() const noexcept {
  return count_ == 0 ? Duration{0} : Duration{total_.count() / static_cast<std::int64_t>(count_)};
}

Duration LatencyHistogram::percentile(double q) const noexcept {
  if (count_ == 0) return Duration{0};
  const double clamped = std::clamp(q, 0.0, 1.0);
  // The rank of the sample at quantile q (1-based), at least the first sample.
  const auto rank = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(clamped * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < kBins; ++b) {
    seen += bins_[b];
    if (seen >= rank) return std::min(upper_edge(b), max_);
  }
  return max_;
}

}  // namespace cellctl::loop

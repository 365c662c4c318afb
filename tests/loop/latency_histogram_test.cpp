#include "loop/latency_histogram.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cellctl::loop {
namespace {

using namespace std::chrono_literals;

// The upper edge of the log bin holding d, computed independently of the implementation's table.
link::Duration expected_upper_edge(link::Duration d) {
  const double in_100ns = static_cast<double>(d.count()) / 100.0;
  const double k = std::floor(std::log10(in_100ns) * 20.0 + 1e-9) + 1.0;
  return link::Duration{std::llround(100.0 * std::pow(10.0, k / 20.0))};
}

TEST(LatencyHistogram, PercentilesOfKnownData) {
  LatencyHistogram h;
  for (int i = 0; i < 990; ++i) h.record(10us);
  for (int i = 0; i < 9; ++i) h.record(500us);
  h.record(50ms);
  EXPECT_EQ(h.count(), 1000u);
  EXPECT_EQ(h.percentile(0.5), expected_upper_edge(10us));     // 11.22 us: one bin above 10 us
  EXPECT_EQ(h.percentile(0.99), expected_upper_edge(10us));    // the 990th sample is still 10 us
  EXPECT_EQ(h.percentile(0.999), expected_upper_edge(500us));  // the 999th is 500 us
  EXPECT_EQ(h.percentile(1.0), 50ms);                          // capped at the exact max
  EXPECT_EQ(h.max(), 50ms);
  EXPECT_EQ(h.mean(), 64400ns);  // (990 x 10 us + 9 x 500 us + 50 ms) / 1000
}

TEST(LatencyHistogram, UniformDataWithinOneBin) {
  LatencyHistogram h;
  for (int us = 1; us <= 1000; ++us) h.record(link::Duration{us * 1000});
  const auto p50 = h.percentile(0.5);
  EXPECT_GE(p50, 500us);
  EXPECT_LE(p50, 500us * 1.13);  // a bin is 10^(1/20) = 1.122 wide
  const auto p99 = h.percentile(0.99);
  EXPECT_GE(p99, 990us);
  EXPECT_LE(p99, 1000us);  // capped at max
}

TEST(LatencyHistogram, EdgesAndOutOfRangeValues) {
  EXPECT_EQ(LatencyHistogram::bin_of(0ns), 0u);
  EXPECT_EQ(LatencyHistogram::bin_of(99ns), 0u);
  EXPECT_EQ(LatencyHistogram::bin_of(100ns), 1u);  // a decade edge opens its bin
  EXPECT_EQ(LatencyHistogram::bin_of(10us), 41u);
  EXPECT_EQ(LatencyHistogram::lower_edge(41), 10us);
  EXPECT_EQ(LatencyHistogram::upper_edge(40), 10us);
  EXPECT_EQ(LatencyHistogram::bin_of(100ms), LatencyHistogram::kBins - 1);
  EXPECT_EQ(LatencyHistogram::bin_of(5s), LatencyHistogram::kBins - 1);

  LatencyHistogram h;
  h.record(-3us);  // a clock that woke early counts as on time
  h.record(2s);
  EXPECT_EQ(h.bin_count(0), 1u);
  EXPECT_EQ(h.bin_count(LatencyHistogram::kBins - 1), 1u);
  EXPECT_EQ(h.percentile(0.5), 100ns);  // the underflow bin's upper edge
  EXPECT_EQ(h.percentile(1.0), 2s);
  EXPECT_EQ(LatencyHistogram{}.percentile(0.99), 0ns);
}

}  // namespace
}  // namespace cellctl::loop

#include "loop/loop.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace cellctl::loop {
namespace {

double to_us(link::Duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

std::string percentiles(const LatencyHistogram& h) {
  return fmt::format("p50 {:.1f} us, p99 {:.1f} us, p99.9 {:.1f} us, max {:.1f} us", to_us(h.percentile(0.5)),
                     to_us(h.percentile(0.99)), to_us(h.percentile(0.999)), to_us(h.max()));
}

}  // namespace

Loop::Loop(const link::Clock& clock, CycleWaiter& waiter, link::Duration period,
           std::span<const std::string_view> stage_names, const link::Clock* stage_clock)
    : clock_(clock),
      waiter_(waiter),
      period_(period),
      stages_(stage_clock ? *stage_clock : clock, stage_names) {
  if (period <= link::Duration{0}) {
    throw std::invalid_argument(fmt::format("loop period: must be > 0, got {} ns", period.count()));
  }
}

void Loop::record_wake(link::TimePoint deadline, link::TimePoint woke) noexcept {
  stats_.jitter.record(woke - deadline);
  if (has_last_wake_) stats_.period_error.record(std::chrono::abs(woke - last_wake_ - period_));
  has_last_wake_ = true;
  last_wake_ = woke;
}

link::TimePoint Loop::schedule_after(link::TimePoint deadline, link::TimePoint end) noexcept {
  const NextDeadline next = next_deadline(deadline, end, period_);
  if (next.missed > 0) {
    ++stats_.overrun_cycles;
    stats_.missed_deadlines += next.missed;
  }
  return next.deadline;
}

std::string Loop::summary() const {
  const double period_us = to_us(period_);
  std::string out = fmt::format("cycles {}, period {:.1f} us, overrun cycles {}, missed deadlines {}\n",
                                stats_.cycles, period_us, stats_.overrun_cycles, stats_.missed_deadlines);
  out += fmt::format("wake-up jitter: {} (p99 / period {:.2f} %)\n", percentiles(stats_.jitter),
                     100.0 * to_us(stats_.jitter.percentile(0.99)) / period_us);
  out += fmt::format("period error:   {}\n", percentiles(stats_.period_error));
  for (std::size_t s = 0; s < stages_.size(); ++s) {
    const LatencyHistogram& h = stages_.histogram(s);
    out += fmt::format("stage {:<16} mean {:.2f} us, {}\n", stages_.name(s), to_us(h.mean()), percentiles(h));
  }
  return out;
}

}  // namespace cellctl::loop

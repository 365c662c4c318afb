#pragma once
// The control cycle: waits for absolute deadlines on a period grid, runs the cycle body, times it,
// counts overruns and skips ahead after them. Time comes only from the injected Clock and
// CycleWaiter, so the same Loop runs in real time and in virtual time.
//
// After construction nothing allocates and nothing is logged: statistics live in fixed-size
// histograms and are turned into text by summary(), outside the cycle.

#include <atomic>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "link/clock.hpp"
#include "loop/control_stages.hpp"
#include "loop/cycle_waiter.hpp"
#include "loop/deadline_schedule.hpp"
#include "loop/latency_histogram.hpp"
#include "loop/stage_times.hpp"

namespace cellctl::loop {

struct LoopStats {
  std::uint64_t cycles = 0;            // bodies run
  std::uint64_t overrun_cycles = 0;    // cycles that ran past their next deadline
  std::uint64_t missed_deadlines = 0;  // deadlines skipped because of them
  LatencyHistogram period_error;       // |time between consecutive wake-ups - period|
  LatencyHistogram jitter;             // wake-up minus deadline
};

class Loop {
 public:
  // Throws std::invalid_argument when period <= 0 or the stage list is invalid (see StageTimes).
  // stage_clock times the stages (compute time); by default the loop's clock. A cycle on a virtual
  // clock passes the monotonic clock here: its compute time is real even when its time is not.
  Loop(const link::Clock& clock, CycleWaiter& waiter, link::Duration period,
       std::span<const std::string_view> stage_names = kControlStages,
       const link::Clock* stage_clock = nullptr);

  // Runs body(now, cycle_index) once per period until `stop` is set (checked at each cycle
  // boundary: before waiting and on waking) or max_cycles bodies have run (0: no limit). The first
  // cycle starts at once; the grid is anchored there. May be called again: the grid restarts, the
  // statistics accumulate.
  template <class Body>
  void run(Body&& body, const std::atomic<bool>& stop, std::uint64_t max_cycles = 0) {
    link::TimePoint deadline = clock_.now();
    const std::uint64_t last = max_cycles == 0 ? UINT64_MAX : stats_.cycles + max_cycles;
    while (stats_.cycles < last && !stop.load(std::memory_order_relaxed)) {
      waiter_.wait_until(deadline);
      if (stop.load(std::memory_order_relaxed)) break;
      const link::TimePoint woke = clock_.now();
      record_wake(deadline, woke);
      body(woke, stats_.cycles);
      ++stats_.cycles;
      deadline = schedule_after(deadline, clock_.now());
    }
    has_last_wake_ = false;
  }

  // For the cycle body: `auto t = loop.time_stage(index(ControlStage::monitor));`
  [[nodiscard]] ScopedStageTimer time_stage(std::size_t stage) noexcept { return stages_.time(stage); }
  // For a body whose stages follow each other: `auto seq = loop.stage_sequence(); seq.begin(…);`
  [[nodiscard]] StageSequence stage_sequence() noexcept { return StageSequence(stages_); }

  [[nodiscard]] link::Duration period() const noexcept { return period_; }
  [[nodiscard]] const LoopStats& stats() const noexcept { return stats_; }
  [[nodiscard]] const StageTimes& stages() const noexcept { return stages_; }

  // Human-readable statistics: jitter and period percentiles, p99 jitter / period, stage times.
  [[nodiscard]] std::string summary() const;

 private:
  void record_wake(link::TimePoint deadline, link::TimePoint woke) noexcept;
  [[nodiscard]] link::TimePoint schedule_after(link::TimePoint deadline, link::TimePoint end) noexcept;

  const link::Clock& clock_;
  CycleWaiter& waiter_;
  link::Duration period_;
  StageTimes stages_;
  LoopStats stats_;
  bool has_last_wake_ = false;  // a previous wake-up exists in this run (for the period histogram)
  link::TimePoint last_wake_{};
};

}  // namespace cellctl::loop

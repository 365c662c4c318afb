#pragma once
// Compute time per named stage of the control cycle. The cycle body wraps each stage in a scoped
// timer; the time is read from the loop's injected clock, so in virtual time a stage costs exactly
// what the body advanced the clock by. Fixed capacity: nothing allocates after construction.

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "link/clock.hpp"
#include "loop/latency_histogram.hpp"

namespace cellctl::loop {

class StageTimes;

// Measures from construction to destruction and records it against one stage.
class [[nodiscard]] ScopedStageTimer {
 public:
  ScopedStageTimer(StageTimes& times, std::size_t stage) noexcept;
  ~ScopedStageTimer();
  ScopedStageTimer(const ScopedStageTimer&) = delete;
  ScopedStageTimer& operator=(const ScopedStageTimer&) = delete;

 private:
  StageTimes& times_;
  std::size_t stage_;
  link::TimePoint start_;
};

// Times stages that follow each other without a gap with one clock read per boundary instead of two
// per stage: in a virtual-time run the clock reads are a fair part of a cycle's cost.
//   auto seq = loop.stage_sequence(); seq.begin(0); …; seq.begin(1); …   (the last ends with seq)
class [[nodiscard]] StageSequence {
 public:
  explicit StageSequence(StageTimes& times) noexcept : times_(times) {}
  ~StageSequence();
  StageSequence(const StageSequence&) = delete;
  StageSequence& operator=(const StageSequence&) = delete;
  // Ends the running stage, if any, and starts `stage`.
  void begin(std::size_t stage) noexcept;

 private:
  static constexpr std::size_t kNone = ~std::size_t{0};
  StageTimes& times_;
  std::size_t stage_ = kNone;
  link::TimePoint start_{};
};

class StageTimes {
 public:
  static constexpr std::size_t kMaxStages = 8;

  // Throws std::invalid_argument when there are more than kMaxStages names or a name is empty.
  StageTimes(const link::Clock& clock, std::span<const std::string_view> names);

  // Precondition: stage < size().
  [[nodiscard]] ScopedStageTimer time(std::size_t stage) noexcept { return ScopedStageTimer(*this, stage); }
  void record(std::size_t stage, link::Duration d) noexcept { histograms_[stage].record(d); }

  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] const std::string& name(std::size_t stage) const noexcept { return names_[stage]; }
  [[nodiscard]] const LatencyHistogram& histogram(std::size_t stage) const noexcept {
    return histograms_[stage];
  }
  [[nodiscard]] const link::Clock& clock() const noexcept { return clock_; }

 private:
  const link::Clock& clock_;
  std::array<std::string, kMaxStages> names_;
  std::array<LatencyHistogram, kMaxStages> histograms_{};
  std::size_t size_ = 0;
};

}  // namespace cellctl::loop

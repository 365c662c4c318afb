#include "loop/stage_times.hpp"

#include <stdexcept>

namespace cellctl::loop {

ScopedStageTimer::ScopedStageTimer(StageTimes& times, std::size_t stage) noexcept
    : times_(times), stage_(stage), start_(times.clock().now()) {}

ScopedStageTimer::~ScopedStageTimer() {
  times_.record(stage_, times_.clock().now() - start_);
}

StageSequence::~StageSequence() {
  if (stage_ != kNone) times_.record(stage_, times_.clock().now() - start_);
}

void StageSequence::begin(std::size_t stage) noexcept {
  const auto now = times_.clock().now();
  if (stage_ != kNone) times_.record(stage_, now - start_);
  stage_ = stage;
  start_ = now;
}

StageTimes::StageTimes(const link::Clock& clock, std::span<const std::string_view> names) : clock_(clock) {
  if (names.size() > kMaxStages) {
    throw std::invalid_argument("loop stages: at most " + std::to_string(kMaxStages) + " stages, got " +
                                std::to_string(names.size()));
  }
  for (const std::string_view n : names) {
    if (n.empty())
      throw std::invalid_argument("loop stages: stage " + std::to_string(size_) + " has no name");
    names_[size_++] = std::string(n);
  }
}

}  // namespace cellctl::loop

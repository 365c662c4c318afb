#pragma once
// What the terminal, the page and the plant show while a run goes on, published by the control cycle
// (runtime) and read on other threads. A sequence lock: the cycle never waits, a reader retries on a
// torn copy. A part of its own, so that its readers see the board and not the runtime that fills it.

#include <array>
#include <atomic>
#include <cstdint>
#include <string_view>

#include "cell/cell_state.hpp"
#include "monitor/rule.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::status {

// The loop's wake-up jitter as cumulative counts at these upper bounds (µs) and one for all, for the
// web page's /metrics (Prometheus histogram buckets).
inline constexpr std::array<double, 9> kJitterBucketsUs = {10, 20, 50, 100, 200, 500, 1000, 2000, 5000};

struct StatusView {
  double t = 0.0;
  supervisor::State state = supervisor::State::idle;
  std::uint32_t step = 0;  // 1-based, 0 before the first
  std::uint32_t steps = 0;
  std::string_view label;       // the program's label (lives as long as the run)
  double step_planned_s = 0.0;  // known once the step started (a move's profile); 0: none
  std::uint8_t axes = 0;
  std::array<double, cell::kMaxAxes> position_mm{};
  std::array<bool, cell::kMaxAxes> position_known{};  // the SCU has reported the actuator
  // Each axis as the page names it apart: where the move in progress goes (target_known: a move is
  // asked for), the SCU's own position, the encoder's where it measures the axis, and the two facts
  // that make it homed — the home record's entry and the SCU's initialised bit.
  std::array<double, cell::kMaxAxes> target_mm{};
  std::array<bool, cell::kMaxAxes> target_known{};
  std::array<double, cell::kMaxAxes> scu_mm{};
  std::array<double, cell::kMaxAxes> encoder_mm{};
  std::array<bool, cell::kMaxAxes> encoder_measures{};
  std::array<bool, cell::kMaxAxes> home_recorded{};
  std::array<bool, cell::kMaxAxes> scu_initialised{};
  double spindle_hz = 0.0;
  double spindle_set_hz = 0.0;
  double jitter_max_us = 0.0;  // the loop's largest wake-up jitter so far
  std::array<std::uint64_t, kJitterBucketsUs.size() + 1> jitter_le{};  // cumulative; the last is every cycle
  double jitter_sum_s = 0.0;
  std::uint64_t overruns = 0;
  // Per device slot (cell::CellState::devices): its name ("" for an empty slot) and its link.
  std::array<std::string_view, cell::kMaxDevices> devices{};
  std::array<bool, cell::kMaxDevices> link_active{};      // the device's session is in its active state
  std::array<bool, cell::kMaxDevices> link_fault{};       // a device's session gave up on its link
  std::array<double, cell::kMaxDevices> link_silent_s{};  // since its last good reply
  std::array<cell::LinkCounts, cell::kMaxDevices> link_counts{};
  std::array<double, cell::kMaxDevices> link_round_trip_s{};  // the last exchange's; 0 before the first
  // The device's safe state once the run's stop has resolved it: "observed", "bounded" or "unknown"
  // (static text, device_seam::to_string(Safe)); "" while it is not resolved.
  std::array<std::string_view, cell::kMaxDevices> safe{};
  bool fault = false;
  monitor::Rule first_fault = monitor::Rule::operator_stop;
};

class StatusBoard {
 public:
  void publish(const StatusView& v) noexcept {
    const auto s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    view_ = v;
    seq_.store(s + 2, std::memory_order_release);
  }
  [[nodiscard]] StatusView read() const noexcept {
    for (;;) {
      const auto before = seq_.load(std::memory_order_acquire);
      if (before & 1u) continue;
      StatusView copy = view_;
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == before) return copy;
    }
  }

 private:
  std::atomic<std::uint64_t> seq_{0};
  StatusView view_;
};

}  // namespace cellctl::status

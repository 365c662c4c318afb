#pragma once
// The safety monitor: a function of CellState and the cell's limits, evaluated every cycle before
// the supervisor, which it always overrides. A violated rule latches with the stop category the
// config gives it (IEC 60204-1: 0 immediate, 1 controlled then off, 2 controlled and hold); a latch
// is cleared only by an operator reset while its cause is gone. No allocation, no I/O.

#include <array>
#include <bitset>
#include <optional>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_core.hpp"
#include "journal/event.hpp"
#include "monitor/rule.hpp"

namespace cellctl::monitor {

using config::StopCategory;

struct Latch {
  bool active = false;
  StopCategory category = StopCategory::controlled_off;
  double since_s = 0.0;
  journal::Text detail;
};

// Requests that do not come from the cell's state.
struct OperatorInputs {
  bool stop = false;  // Ctrl-C / stop command
  bool emergency_stop = false;
};

class Monitor {
 public:
  explicit Monitor(const config::CellCore& cell);

  // Device rules apply once the cell is up (the supervisor arms the monitor when every session is
  // active and the encoder is ready); operator and emergency stops apply always.
  void arm() noexcept { armed_ = true; }
  void disarm() noexcept { armed_ = false; }
  [[nodiscard]] bool armed() const noexcept { return armed_; }
  // The spindle frequency rule needs to know what the supervisor asked for.
  void expect_spindle(bool running, double set_hz) noexcept {
    spindle_running_ = running;
    spindle_set_hz_ = set_hz;
  }
  // The following-error rule needs the supervisor's plan: while no halt is asked for, the axes with
  // `move` set are held to their planned position.
  void expect_axes(const cell::Intents& intents) noexcept {
    planned_ = intents.axes;
    following_ = intents.halt == cell::Halt::none;
  }

  // Evaluates every rule at `t` (seconds since start); returns the rules that latched in this call.
  std::bitset<kRuleCount> evaluate(const cell::CellState& state, const OperatorInputs& inputs,
                                   double t) noexcept;

  // The strongest stop the latched faults demand (lowest category), or none.
  [[nodiscard]] std::optional<StopCategory> demanded_stop() const noexcept;
  [[nodiscard]] const Latch& latch(Rule r) const noexcept { return latches_[static_cast<std::size_t>(r)]; }
  [[nodiscard]] bool any_latched() const noexcept { return demanded_stop().has_value(); }

  // Operator reset: clears every latch whose cause is gone in `state`; returns true when none is left.
  bool reset(const cell::CellState& state, const OperatorInputs& inputs) noexcept;

 private:
  // Fills `causes` with the rules violated in `state` right now, with details.
  void check(const cell::CellState& state, const OperatorInputs& inputs,
             std::array<std::optional<journal::Text>, kRuleCount>& causes) const noexcept;
  [[nodiscard]] StopCategory category_of(Rule r) const noexcept;

  const config::CellCore& cell_;
  std::array<Latch, kRuleCount> latches_{};
  bool armed_ = false;
  bool spindle_running_ = false;
  double spindle_set_hz_ = 0.0;
  std::array<cell::AxisIntent, cell::kMaxAxes> planned_{};
  bool following_ = false;
};

}  // namespace cellctl::monitor

#pragma once
// The guided Teach-In of the encoder (manual 4.4.2) as a state machine stepped once per control
// cycle, like the supervisor: it reads the CellState, writes Intents, and asks the encoder for its
// parameter switches and the Teach-In handshakes through a TeachInPort.
//
//   checking → to_start → switching → starting → travelling → ending → switching_taught → returning
//   → verifying → done;  any fault, operator abort or failed check → halting → restoring → failed
//
// Moves go through the motion part's MoveExecutor (one move primitive), closed on the SCU's position:
// while the encoder is being taught its reading is unscaled or in its new unit, so the SCU's
// position is the reference, and the monitor guards the axis on it. The native zero must not be
// crossed (4.4.2.1): the travel is checked against it before the move and watched during it. The
// result is verified by moving back: the taught encoder must measure the SCU's distance within the
// tolerance. On any failure once the encoder was switched, its configured parameters are restored.

#include <cstdint>
#include <optional>
#include <string_view>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_core.hpp"
#include "journal/event.hpp"
#include "motion/move_executor.hpp"
#include "recipe/recipe.hpp"
#include "routines/teach_in_port.hpp"

namespace cellctl::routines {

// What to teach: a recipe's Teach-In step.
using TeachInRequest = recipe::TeachIn;

enum class TeachInPhase : std::uint8_t {
  checking,
  to_start,
  switching,
  starting,
  travelling,
  ending,
  switching_taught,
  returning,
  verifying,
  done,
  halting,
  restoring,
  failed,
};
[[nodiscard]] std::string_view to_string(TeachInPhase p) noexcept;

struct TeachInResult {
  std::uint32_t total_resolution = 0;
  double scu_distance_mm = 0.0;      // the travel taught (SCU)
  double encoder_distance_mm = 0.0;  // the taught encoder's measure of the way back
  double scu_back_mm = 0.0;          // the SCU's measure of the way back
};

class TeachIn {
 public:
  TeachIn(const config::CellCore& cell, TeachInPort& port, const TeachInRequest& request, double dt);

  // One cycle. `demanded`: the monitor's stop, if any (then the routine halts and fails).
  void step(const cell::CellState& s, std::optional<config::StopCategory> demanded,
            std::string_view stop_reason, double t);
  // The operator aborts (Ctrl-C): halt, restore, fail.
  void abort(double t);
  // Manual mode: the operator has moved the axis as asked.
  void confirm() noexcept { confirmed_ = true; }

  // The state as the monitor and the routine see it while the encoder is being taught: the axis is
  // known by the SCU's position, and the encoder counts as ready while it exchanges data (its
  // inputs are flagged "Teach-In running, unscaled" by design).
  void adjust(cell::CellState& s) const noexcept;
  // The monitor is armed while the routine moves the axis (not while the encoder is re-parameterised:
  // it leaves data exchange on purpose then).
  [[nodiscard]] bool moving() const noexcept;
  [[nodiscard]] bool finished() const noexcept {
    return phase_ == TeachInPhase::done || phase_ == TeachInPhase::failed;
  }
  [[nodiscard]] TeachInPhase phase() const noexcept { return phase_; }
  // Where the routine's present move plans the axis (for the journal's samples).
  [[nodiscard]] double planned_mm(std::size_t axis) const noexcept { return executor_.planned_mm(axis); }
  [[nodiscard]] const cell::Intents& intents() const noexcept { return intents_; }
  [[nodiscard]] const journal::Text& failure() const noexcept { return failure_; }
  [[nodiscard]] const TeachInResult& result() const noexcept { return result_; }
  // What the operator should do now (manual mode), empty when nothing.
  [[nodiscard]] const journal::Text& prompt() const noexcept { return prompt_; }
  // The parameters the encoder has now are not the configured ones (a restore is owed).
  [[nodiscard]] bool switched() const noexcept { return switched_; }

 private:
  void enter(TeachInPhase p, double t) noexcept;
  void fail(double t, const journal::Text& why) noexcept;
  void start_move(const cell::CellState& s, double target_mm, double t);
  // running: nullopt; done: true; failed (failure_ set): false.
  [[nodiscard]] std::optional<bool> step_move(const cell::CellState& s, double t);
  // Fails the Teach-In once its phase has waited longer than limit_s for `what`.
  void fail_after(double t, double limit_s, const char* what);
  void step_checking(const cell::CellState& s, double t);

  const config::CellCore& cell_;
  TeachInPort& port_;
  TeachInRequest request_;
  recipe::Limits limits_;
  motion::MoveExecutor executor_;
  cell::Intents intents_;
  std::uint32_t move_id_ = 0;
  bool move_active_ = false;

  TeachInPhase phase_ = TeachInPhase::checking;
  double phase_since_ = 0.0;
  bool confirmed_ = false;
  bool switched_ = false;
  double start_mm_ = 0.0;        // the start (SCU)
  double scu_at_start_ = 0.0;    // when Teach-In started
  double native_last_mm_ = 0.0;  // for the crossing watch
  double scu_at_end_ = 0.0;
  double encoder_at_end_ = 0.0;  // taught, at the end point
  TeachInResult result_;
  journal::Text failure_;
  journal::Text prompt_;
};

}  // namespace cellctl::routines

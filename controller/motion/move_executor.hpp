#pragma once
// One recipe move, closed on the encoder. The planner gives the jerk-limited profile the recipe asks
// for (`path: time`: time synchronisation, `path: line`: phase synchronisation, a straight line in
// joint space) — the journal's "planned" positions, and the pace each axis is kept on; the SCU gets
// the targets and a speed per axis scaled so coordinated axes arrive together, modulated during the
// move to keep each on its planned profile. The move is done only when every axis is inside its
// tolerance by its best measurement (the encoder where it has one). When the SCU has stopped but the
// encoder says the axis is off (scale error, slip), the SCU target is corrected by the measured error
// and the axis moved again, a bounded number of times. Where the encoder measures an axis that moves
// steadily and the cell config allows it (correct_in_motion), how its SCU reading drifts along the
// travel (a scale error) is learnt on the way, and the
// SCU's target corrected while the axis still moves: it then arrives with the others, not a correction
// later. A move that produces no motion is detected.
// A hold brakes the move (the SCU's soft stop, which the plan follows); resume() goes on from the
// moving state the brake has reached: no stop first.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_core.hpp"
#include "journal/event.hpp"
#include "link/clock.hpp"
#include "motion/offset_slope.hpp"
#include "planner/planner.hpp"
#include "recipe/recipe.hpp"

namespace cellctl::motion {

struct MoveSettings {
  int max_corrections = 3;
  double no_motion_s = 1.5;        // no measurable progress for this long → "no motion"
  double settle_s = 0.15;          // the SCU must show no motion for this long before we judge
  double speed_update_s = 0.1;     // at most this often a new speed goes to the SCU
  double sync_gain = 2.0;          // speed correction per unit of normalised lag
  double max_scale_error = 0.015;  // a larger drift of the SCU from the encoder is not corrected in motion
  // No correction in motion over a slower SCU line (RC round trip; 38400 Bd with a USB adapter: 10-25 ms).
  double max_round_trip_to_correct_s = 0.025;
};

enum class MoveStatus : std::uint8_t { running, done, failed };

// What a move is judged by: the best measurement (the encoder where it measures the axis), or the SCU's
// own position — for homing, before the encoder has been referenced.
enum class Reference : std::uint8_t { best, scu };

class MoveExecutor {
 public:
  MoveExecutor(const config::CellCore& cell, const recipe::Limits& limits, double dt,
               MoveSettings settings = {});

  // Starts `move` from the state's current positions. `move_id` is the cell's move counter: every
  // command to an axis takes the next value, so CellDevices sees each new command exactly once.
  void start(const recipe::Move& move, const cell::CellState& s, double t, std::uint32_t& move_id,
             Reference reference = Reference::best);
  // One cycle: updates the intents of the axes in the move. On failure, reason() says why.
  [[nodiscard]] MoveStatus step(const cell::CellState& s, double t, cell::Intents& out,
                                std::uint32_t& move_id);
  // One cycle of a hold (the supervisor stops the axes: the SCU brakes each at its soft ramp): the
  // plan follows that brake from the planned state the hold found.
  void hold(double t) noexcept;
  // After a hold: the move goes on to its targets from the measured positions and the brake's
  // velocities and accelerations — re-planned from the moving state, no stop first.
  void resume(const cell::CellState& s, double t, std::uint32_t& move_id);

  [[nodiscard]] const journal::Text& reason() const noexcept { return reason_; }
  // What the last step() has to say: the planner's note on a new plan (phase synchronisation
  // impossible: time synchronised instead), or an SCU target corrected while moving; empty when
  // that step did neither.
  [[nodiscard]] std::string_view note() const noexcept { return note_.view(); }
  [[nodiscard]] int corrections() const noexcept { return corrections_total_; }
  // The move's planned time: the slowest axis's trapezoid at the move speed (as the SCU runs it).
  [[nodiscard]] double planned_s() const noexcept { return planned_s_; }
  // Where the profile says each axis should be now (for the journal's samples).
  [[nodiscard]] double planned_mm(std::size_t axis) const noexcept { return planned_[axis]; }

 private:
  struct Axis {
    bool in_move = false;
    double start_mm = 0.0;
    double target_mm = 0.0;      // the recipe's target (true position)
    double scu_target_mm = 0.0;  // what the SCU is told (target + corrections)
    double nominal_speed = 0.0;  // its share of the move speed, so that all arrive together
    double tolerance_mm = 0.0;
    int corrections = 0;  // SCU targets corrected, at rest or in motion
    // The command that corrected it in motion, 0 before (at most one per move).
    std::uint32_t in_motion_move_id = 0;
    bool correcting_at_rest = false;  // a correction at rest is under way (no speed modulation)
    bool anchored = false;            // the plan began at rest: start_scu_mm and start_mm are one instant
    double start_scu_mm = 0.0;        // the SCU's reading then
    double sampled_mm_s = 0.0;        // the encoder's speed at the last drift sample
    OffsetSlope drift;                // SCU − encoder along the travel, while moving steadily
    bool commanded = false;           // told to move (an axis already inside its tolerance is left alone)
    double commanded_at = 0.0;        // when the last command to it went out
    std::uint32_t taken_before = 0;   // the SCU's count of moves taken when the plan commanded it
    std::uint32_t move_id = 0;        // bumped for every command to this axis (start, correction)
  };

  // Where an axis stands and how it moves when a plan begins.
  struct Motion {
    double velocity = 0.0;
    double acceleration = 0.0;
  };
  using Motions = std::array<Motion, cell::kMaxAxes>;

  [[nodiscard]] double best_position(const cell::CellState& s, std::size_t i) const noexcept;
  void command(cell::Intents& out) const noexcept;
  // Plans from the axes' positions in `s` and `from`, sets the SCU speeds so that all arrive together,
  // and commands every axis not yet inside its tolerance (or still moving).
  void plan(const cell::CellState& s, double t, std::uint32_t& move_id, const Motions& from);
  // Learns each measured axis's drift from a fresh SCU reading, and gives the SCU a corrected target
  // while the axis moves once the drift is known well enough (see the file comment).
  void correct_in_motion(const cell::CellState& s, double t, std::uint32_t& move_id);
  // An SCU target for axis i, kept within what the monitor tolerates between SCU and encoder
  // beyond the travel: the SCU is never sent a target outside the axis's reach.
  [[nodiscard]] double reachable_scu_target(std::size_t i, double mm) const noexcept;
  // A new SCU target for axis i (reachable), commanded now: a correction.
  void retarget(std::size_t i, double scu_target_mm, double t, std::uint32_t& move_id);
  // Starts the clock of each commanded axis whose move the SCU has just taken (a new RE acknowledged),
  // and sets every clocked axis's planned state at t (see clock_from_).
  void follow_plan(const cell::CellState& s, double t);
  // The SCU's soft stop of axis i, `since` seconds after the hold: its planned state then.
  [[nodiscard]] planner::MotionState braked(std::size_t i, double since) const noexcept;

  const config::CellCore& cell_;
  const recipe::Limits& limits_;
  Reference reference_ = Reference::best;
  MoveSettings settings_;
  planner::Planner<6> planner_;
  planner::Input<6> input_;
  planner::Output<6> output_;
  std::array<Axis, cell::kMaxAxes> axes_{};
  std::array<double, cell::kMaxAxes> planned_{};
  std::array<double, cell::kMaxAxes> planned_speed_{};
  std::array<double, cell::kMaxAxes> speed_sent_{};
  double speed_ = 0.0;
  double planned_s_ = 0.0;
  double started_t_ = 0.0;
  // Each axis's clock on the plan. An axis commanded from rest is on its plan from when the SCU has
  // taken its move (its RE answered): the SCU takes the axes one after the other, each after its own
  // telegrams, so a slow line is no following error. One moving already (a resume) or not commanded
  // is on it at once. The plan is read at the cell's time, not counted in cycles: a cycle the loop
  // missed under load moved the axes all the same.
  std::array<std::optional<double>, cell::kMaxAxes> clock_from_{};
  bool calculated_ = false;  // the planner has the plan's trajectory
  double last_progress_t_ = 0.0;
  double best_remaining_ = 0.0;
  double last_speed_update_t_ = 0.0;
  std::optional<double> still_since_;
  planner::Synchronization synchronization_ = planner::Synchronization::time;
  std::optional<double> held_since_;                              // the hold's start, while held
  std::array<planner::MotionState, cell::kMaxAxes> held_from_{};  // the planned position and speed then
  journal::Text note_;
  link::Duration last_scu_age_{};  // the SCU reading's age last cycle: it drops when a fresh one is in
  std::array<bool, cell::kMaxAxes> seen_moving_{};  // the SCU showed motion since the last command
  int corrections_total_ = 0;
  journal::Text reason_;
};

}  // namespace cellctl::motion

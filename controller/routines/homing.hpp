#pragma once
// Homing as its own state machine (as LinuxCNC homes joints): the axes asked for are homed group by
// group in the order of their `homing.sequence` (the same number: together), each by its strategy:
//   absolute_encoder  no motion: the encoder in data exchange, ready, inside the travel, and agreeing
//                     with the home record where there is one;
//   end_position      back off an end it already stands at, drive into the end at the homing speed
//                     (judged on the SCU's position: the encoder is not referenced yet), wait until
//                     the SCU reports the end ("in"/"out position") and rest, preset the encoder to
//                     preset_mm there and read it back, then move to home_mm on the encoder;
//   scu_initialised   the SCU's status 2 "initialised" is the reference: an actuator not initialised
//                     is driven into its retracted end (our reading of the SCU manual, which does not
//                     say how it initialises: README "Homing", devices/scu/emulator.hpp), and must then
//                     report it; then to home_mm.
// Motion goes through the motion part's MoveExecutor (planner profile, closed on the measurement), so
// an operator stop, a fault or Ctrl-C stops it like any recipe move: the supervisor's halt stops every
// axis. Before any motion it refuses, with the reason, when the spindle turns, a device is not ready
// or a limit is active. Each finished group is written into the HomeRecord; the axes being homed lose
// their old entry at the start (a half-done homing leaves them not homed). Cell types only; no I/O,
// no allocation after construction.

#include <array>
#include <cstdint>
#include <span>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_core.hpp"
#include "journal/event_sink.hpp"
#include "motion/move_executor.hpp"
#include "recipe/recipe.hpp"
#include "routines/home_record.hpp"

namespace cellctl::routines {

enum class HomingPhase : std::uint8_t {
  idle,      // not asked for
  waiting,   // its sequence has not come yet
  back_off,  // leaving the end it stood at, to drive into it again
  to_end,    // driving into the end
  at_end,    // waiting for the SCU to report the end (and initialised) at rest
  preset,    // the encoder's preset handshake, then its read-back
  to_home,   // moving to the home position
  homed,
  failed,
};
[[nodiscard]] const char* to_string(HomingPhase p) noexcept;

enum class HomingStatus : std::uint8_t { running, done, failed };

class Homing {
 public:
  Homing(const config::CellCore& cell, journal::EventSink& events, double dt, motion::MoveSettings move = {});

  // Begins homing `axes` (cell axis indices, each with a strategy); results go into `record`.
  void start(std::span<const int> axes, double t, HomeRecord& record);
  // One cycle. `move_id` and `preset_id` are the cell's counters (each command takes the next value).
  [[nodiscard]] HomingStatus step(const cell::CellState& s, double t, cell::Intents& out,
                                  std::uint32_t& move_id, std::uint32_t& preset_id);

  [[nodiscard]] const journal::Text& reason() const noexcept { return reason_; }
  [[nodiscard]] HomingPhase phase(std::size_t axis) const noexcept { return phase_[axis]; }
  [[nodiscard]] double planned_mm(std::size_t axis) const noexcept { return executor_.planned_mm(axis); }

 private:
  enum class Stage : std::uint8_t { next_group, back_off, to_end, at_end, preset, preset_read, to_home };

  [[nodiscard]] bool refuse(const cell::CellState& s);
  [[nodiscard]] bool check_absolute(const cell::CellState& s, std::size_t i);
  void begin_group(const cell::CellState& s, double t, std::uint32_t& move_id);
  // Starts one move of every axis in `phase` to its target, judged on `ref`; false when none is.
  bool start_move(HomingPhase phase, const cell::CellState& s, double t, std::uint32_t& move_id,
                  motion::Reference ref);
  [[nodiscard]] double end_mm(std::size_t i) const noexcept;
  [[nodiscard]] bool at_end(const cell::CellState& s, std::size_t i) const noexcept;
  void enter(std::size_t i, HomingPhase p, const cell::CellState& s, double t);
  void finish_group(const cell::CellState& s, double t);
  HomingStatus fail(journal::Text why);

  const config::CellCore& cell_;
  journal::EventSink& events_;
  recipe::Limits limits_;  // the homing moves' tolerances, speeds and time-out, from the cell
  motion::MoveExecutor executor_;
  recipe::Move move_;  // reused: its targets are reserved at construction
  HomeRecord* record_ = nullptr;
  std::array<AxisHome, cell::kMaxAxes> previous_{};  // the record as it was when homing began
  std::array<HomingPhase, cell::kMaxAxes> phase_{};
  std::array<bool, cell::kMaxAxes> in_group_{};
  Stage stage_ = Stage::next_group;
  double stage_since_ = 0.0;
  std::uint32_t preset_id_ = 0;
  std::size_t preset_axis_ = 0;
  journal::Text reason_;
};

}  // namespace cellctl::routines

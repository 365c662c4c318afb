#pragma once
// The sequencer: runs the recipe's unrolled program as a PackML-style state machine, one cycle at a
// time, and says what it wants of the devices as Intents. The monitor's demanded stop overrides it
// every cycle (category 0 → Aborting, 1 → Stopping, 2 → Holding). Pure with respect to devices:
// it reads CellState and writes Intents and events; no I/O, no allocation after construction.

#include <cstdint>
#include <optional>
#include <string_view>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_core.hpp"
#include "journal/event_sink.hpp"
#include "motion/move_executor.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe.hpp"
#include "routines/home_record.hpp"
#include "routines/homing.hpp"
#include "routines/teach_in.hpp"
#include "routines/teach_in_port.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::supervisor {

struct SupervisorSettings {
  double start_timeout_s = 20.0;           // devices up and encoder ready
  double stop_timeout_s = 30.0;            // axes still and spindle at rest after a stop
  double sample_s = 0.02;                  // journal sample period
  std::string_view mode = "virtual-time";  // for the run record: virtual-time, emulated, hardware
  motion::MoveSettings move;
  // What `require: homed` checks and `home` steps write (loaded from the state folder by the runtime);
  // nullptr: an empty record of the supervisor's own (nothing homed before this run).
  routines::HomeRecord* home_record = nullptr;
  // The encoder's Teach-In port (the runtime's TeachInEncoder) for a program with a Teach-In step;
  // nullptr: such a step fails, naming why.
  routines::TeachInPort* teach_in_port = nullptr;
};

class Supervisor {
 public:
  Supervisor(const config::CellCore& cell, const recipe::Recipe& recipe, const recipe::Program& program,
             journal::EventSink& events, double dt, SupervisorSettings settings = {});

  // An operator command, carried out at the next step. False when the state does not allow it now;
  // refusal() says why. Reset must only be sent once the monitor's latches are clear.
  bool command(Command c, std::string_view source, double t);
  // `stop_reason`: the monitor's words for the demanded stop (its first active latch), if any.
  void step(const cell::CellState& s, std::optional<config::StopCategory> demanded, double t,
            std::string_view stop_reason = {});
  // The first half of an operator reset: the devices clear their own latched faults (CMD System Reset
  // to the spindle converter) at the next step, before the monitor's latches are judged.
  void reset_devices() noexcept { device_reset_requested_ = true; }

  [[nodiscard]] const cell::Intents& intents() const noexcept { return intents_; }
  [[nodiscard]] State state() const noexcept { return state_; }
  [[nodiscard]] std::size_t step_index() const noexcept { return pc_; }
  [[nodiscard]] std::size_t step_count() const noexcept { return program_.instructions.size(); }
  [[nodiscard]] const recipe::Instruction* current() const noexcept;
  // The device rules of the monitor apply from Execute on (the cell is up), except while a Teach-In
  // re-parameterises the encoder: it leaves data exchange on purpose then.
  [[nodiscard]] bool cell_up() const noexcept {
    return cell_up_ && !(teach_in_ && !teach_in_->finished() && !teach_in_->moving());
  }
  // The state as this program reads it, before the monitor judges it: once a Teach-In step has begun,
  // its axis is known by the SCU's position (the encoder counts in a unit being taught) for the rest
  // of the run.
  void adjust(cell::CellState& s) const noexcept {
    if (teach_in_) teach_in_->adjust(s);
  }
  // Manual Teach-In: the operator has moved the axis as its prompt asked.
  void confirm() noexcept {
    if (teach_in_) teach_in_->confirm();
  }
  // The Teach-In step's routine, once one has begun (its phase, result, failure); nullptr before.
  [[nodiscard]] const routines::TeachIn* teach_in() const noexcept {
    return teach_in_ ? &*teach_in_ : nullptr;
  }
  [[nodiscard]] const journal::Text& failure() const noexcept { return failure_; }
  [[nodiscard]] const journal::Text& refusal() const noexcept { return refusal_; }
  [[nodiscard]] double planned_mm(std::size_t axis) const noexcept;
  // The current step's planned time where it is known once the step has started (a move's); 0 else.
  [[nodiscard]] double step_planned_s() const noexcept;
  [[nodiscard]] const routines::HomeRecord& home_record() const noexcept { return *record_; }
  [[nodiscard]] const routines::Homing& homing() const noexcept { return homing_; }
  [[nodiscard]] int corrections() const noexcept { return corrections_; }

 private:
  enum class StepStatus : std::uint8_t { running, done, failed };

  void enter(State next, double t, const journal::Text& reason = {});
  void start_instruction(const cell::CellState& s, double t);
  StepStatus run_instruction(const cell::CellState& s, double t);
  void apply_demanded(std::optional<config::StopCategory> demanded, double t);
  void sample(const cell::CellState& s, double t);
  [[nodiscard]] bool axes_still(const cell::CellState& s) const noexcept;
  // The current step is a move that has begun (a hold brakes it, an unhold resumes it).
  [[nodiscard]] bool move_started() const noexcept;
  void clear_motion() noexcept;
  // A Teach-In step's cycle in Execute, and while the run halts: the routine halts its axis and
  // restores the encoder's configured parameters before the halting state may end.
  StepStatus run_teach_in(const cell::CellState& s, double t);
  void wind_down_teach_in(const cell::CellState& s, std::optional<config::StopCategory> demanded,
                          std::string_view stop_reason, double t);
  [[nodiscard]] bool teach_in_settled() const noexcept { return !teach_in_ || teach_in_->finished(); }
  void tell_teach_in(double t);

  const config::CellCore& cell_;
  const recipe::Recipe& recipe_;
  const recipe::Program& program_;
  journal::EventSink& events_;
  SupervisorSettings settings_;
  double dt_;
  motion::MoveExecutor executor_;
  routines::Homing homing_;
  std::optional<routines::TeachIn> teach_in_;
  routines::TeachInPhase told_phase_ = routines::TeachInPhase::checking;
  journal::Text told_prompt_;
  routines::HomeRecord own_record_;
  routines::HomeRecord* record_;
  std::uint32_t preset_counter_ = 0;

  State state_ = State::idle;
  double state_since_ = 0.0;
  std::optional<Command> pending_;
  journal::Text pending_source_;
  cell::Intents intents_;
  std::uint32_t move_counter_ = 0;
  std::size_t pc_ = 0;
  bool instruction_started_ = false;
  double instruction_t_ = 0.0;
  double dwell_left_s_ = 0.0;
  double last_execute_t_ = 0.0;
  double next_sample_t_ = 0.0;
  bool cell_up_ = false;
  bool device_reset_requested_ = false;
  int corrections_ = 0;
  journal::Text failure_;
  journal::Text refusal_;
};

}  // namespace cellctl::supervisor

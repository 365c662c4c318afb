#pragma once
// What the plant link and the operator page may reach of the controller: the one command path (the
// arbiter), the live status of the run in progress, and — for a standing controller (`cellctl serve`)
// — the start of a recipe, of homing or of a Teach-In. `cellctl run` drives the one run it was started
// with: fixed_run() gives its access, with no start.
//
// The functions are called on the link's and the page's threads, never on the control loop's.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "command/arbiter.hpp"
#include "status/status_view.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::plant_link {

// The live status of the run in progress, copied out of its board. `view.label` is cleared: the
// program's label lives only as long as its run; `label` holds a copy.
struct LiveRun {
  status::StatusView view;
  std::string label;
};

using Taken = command::Taken;

// What a start asks for; the command desk has checked its shape (and a recipe's validity).
struct StartRecipe {
  std::string name;            // as the plant named it
  std::filesystem::path file;  // <recipes>/<name>.yaml, validated against the cell
  std::size_t steps = 0;       // unrolled
};
struct StartHoming {
  std::vector<std::string> axes;  // empty: every axis that has homing
};
struct StartTeachIn {
  std::string axis;
  double distance_mm = 0.0;
  std::optional<double> from_mm;
  std::optional<double> speed_mm_s;
};
using StartRequest = std::variant<StartRecipe, StartHoming, StartTeachIn>;

struct RunAccess {
  command::Arbiter* arbiter = nullptr;             // the one command path; never null in use
  std::function<std::optional<LiveRun>()> status;  // nullopt: no run in progress
  std::string mode;                                // "hardware", "emulated", "virtual-time"; "" without a run
  // The cell as `cellctl serve` read it before any job (runtime/cell_look.hpp), never live; empty or
  // nullopt: not read (`cellctl run`, or a cell that could not be read).
  std::function<std::optional<status::StatusView>()> at_rest;
  // Registers a job the arbiter allowed (command::Arbiter::start's `begin`), started by `by` (its run's
  // start is told as theirs); empty when this cellctl drives one run and can start no other.
  std::function<Taken(const StartRequest&, const command::CommandSource& by)> start;
};

// The access to one run that exists as long as the access is used: its arbiter and its board.
[[nodiscard]] RunAccess fixed_run(command::Arbiter& arbiter, const status::StatusBoard& board,
                                  std::string mode);

// The board's view, its label copied.
[[nodiscard]] LiveRun live_run(const status::StatusBoard& board);

}  // namespace cellctl::plant_link

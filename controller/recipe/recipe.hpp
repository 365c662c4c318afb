#pragma once
// A recipe as plain data, after loading and validation: units are mm, mm/s, Hz and s; axes are
// indices into the cell config's axes. Nothing here can be out of the cell's or the recipe's limits.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace cellctl::recipe {

struct AxisLimits {
  double min_mm = 0.0;
  double max_mm = 0.0;
  double max_speed_mm_s = 0.0;
  double tolerance_mm = 0.05;  // a move is done when the encoder (or SCU) position is this close
};

struct Limits {
  std::vector<std::optional<AxisLimits>> axes;  // by cell axis index; nullopt: the recipe may not move it
  double spindle_min_hz = 0.0;
  double spindle_max_hz = 0.0;
  double move_timeout_s = 60.0;
  double spindle_timeout_s = 30.0;
};

struct AxisTarget {
  int axis = 0;
  double target_mm = 0.0;
};

// How the axes of one move get from where they are to their targets. Either way they start and
// arrive together; they differ in between.
enum class Path : std::uint8_t {
  time,  // each axis on its own profile, all ending at the same time (the default)
  line,  // a straight line in joint space (`path: line`), when the axes' states allow one
};

// Moves one or several axes; several axes start and arrive together (coordinated).
struct Move {
  std::vector<AxisTarget> targets;
  double speed_mm_s = 0.0;  // path speed of the leading axis
  Path path = Path::time;
};

enum class SpindleDirection : std::uint8_t { cw, ccw };

// Start: set frequency and direction, start, wait until at speed. Stop: stop, wait until at rest.
struct Spindle {
  bool start = true;
  double frequency_hz = 0.0;
  SpindleDirection direction = SpindleDirection::cw;
};

struct Dwell {
  double seconds = 0.0;
};

// Waits for a condition on the cell, failing the run after the time-out.
struct Wait {
  enum class Condition : std::uint8_t {
    position_above,
    position_below,
    encoder_ready,
    spindle_at_speed,
    spindle_at_rest
  };
  Condition condition = Condition::encoder_ready;
  int axis = -1;              // for position conditions
  double threshold_mm = 0.0;  // for position conditions (encoder-measured where the axis has it)
  double timeout_s = 10.0;
};

// Preconditions checked when the step is reached: a run stops instead of moving on doubt.
struct Require {
  std::vector<int> homed_axes;
  bool encoder_ready = false;
  bool spindle_at_rest = false;
};

// Homes the axes as the cell config's `homing:` says (strategies, sequence), then writes the home record.
struct Home {
  std::vector<int> axes;  // cell axis indices, each with a homing strategy
};

// Teaches the encoder its resolution (its guided Teach-In, routines/teach_in.hpp) on the axis it
// measures: travels distance_mm from the start, verifies by moving back. A job of its own (`cellctl
// teach-in`, the plant's teach-in), run as a one-step program by the same cycle as any recipe.
struct TeachIn {
  int axis = 0;                   // index into the cell's axes (the encoder's axis)
  double distance_mm = 0.0;       // travel from the start, in + direction
  std::optional<double> from_mm;  // the start (default: where the axis stands)
  bool manual = false;            // the operator moves the axis; confirm() after each move
  double speed_mm_s = 5.0;
  double tolerance_mm = 0.05;          // verification: encoder distance vs SCU distance
  double native_zero_margin_mm = 0.5;  // the travel keeps this far from the native zero
};

struct Step;
struct Repeat {
  int times = 1;
  std::vector<Step> steps;
};

struct Step {
  std::string name;  // the recipe's own label, or "move", "dwell" … when none is given
  int line = 0;      // where it stands in the recipe file
  std::variant<Move, Spindle, Dwell, Wait, Require, Home, TeachIn, Repeat> action;
};

struct Recipe {
  std::string name;
  std::string version;
  std::string cell;
  std::string source;  // file path, for messages and the run record
  Limits limits;
  std::vector<Step> steps;
};

}  // namespace cellctl::recipe

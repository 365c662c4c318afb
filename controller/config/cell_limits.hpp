#pragma once
// What the safety monitor holds the whole cell to, whatever the recipe says, and how it stops.
// Stop categories follow IEC 60204-1: 0 immediate removal of power (SCU F20 + spindle stop at
// once), 1 controlled stop then off, 2 controlled stop with power kept (hold).

#include <cstdint>

#include "config/yaml_node.hpp"

namespace cellctl::config {

enum class StopCategory : std::uint8_t { immediate = 0, controlled_off = 1, controlled_hold = 2 };

struct CellLimits {
  double overspeed_mm_s = 25.0;    // encoder velocity above this stops the cell
  double disagreement_mm = 2.0;    // SCU-reported vs encoder position on the measured axis
  double link_silence_ms = 300.0;  // any device link silent longer than this is a fault
  double spindle_min_hz = 0.0;     // the spindle's allowed running range
  double spindle_max_hz = 1000.0;
  double spindle_tolerance_hz = 5.0;  // actual vs set frequency while at speed
};

struct StopReactions {
  StopCategory fault = StopCategory::controlled_off;  // a limit or device fault
  StopCategory link = StopCategory::immediate;        // a device that stopped answering
  StopCategory operator_stop = StopCategory::controlled_hold;
  StopCategory following_error = StopCategory::controlled_off;  // an axis off its planned profile
};

struct LoopConfig {
  double period_ms = 1.0;
  bool realtime = true;  // try SCHED_FIFO + mlockall (warn and go on when not permitted)
  int priority = 80;
  int cpu = -1;             // pin to this CPU when ≥ 0
  double sample_ms = 20.0;  // journal sample period
};

[[nodiscard]] CellLimits parse_cell_limits(const YamlNode& n);
[[nodiscard]] StopReactions parse_stop_reactions(const YamlNode& n);
[[nodiscard]] LoopConfig parse_loop(const YamlNode& n);

}  // namespace cellctl::config

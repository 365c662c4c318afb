#pragma once
// The run record's last line, {"event":"summary",…}: what the run amounted to — its outcome and
// duration, the time per step, the faults — and what the run adds of its own: the loop's figures, how
// each device's link did, the safe state each device was left in and what ended the run. One schema:
// the journal fills in the first part (journal/run_summary.hpp), the run the rest (RunFigures), and
// `cellctl report` reads the loop's figures back (LoopFigures).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cellctl::schema {

// A step's time, repeated steps added up under one label.
struct StepTime {
  std::string label;
  int count = 0;
  double seconds = 0.0;
  int failed = 0;
  int interrupted = 0;
  double held_s = 0.0;
};

// How a device's link did over the run.
struct LinkFigures {
  std::string device;  // scu, spindle, encoder
  std::uint64_t replies = 0;
  double max_round_trip_ms = 0.0;
  double max_silence_ms = 0.0;
  std::uint64_t timeouts = 0;
  std::uint64_t retries = 0;
  std::uint64_t bad_frames = 0;
};

// The safe state a device was left in (observed, bounded, unknown) and why it is believed.
struct DeviceVerdict {
  std::string device;
  std::string safe;
  std::string evidence;
};

// What ended a run that did not complete: a link that failed (named as the link, whatever rule
// latched), or a monitor rule (an operator's stop among them).
struct EndedBy {
  double t = 0.0;
  std::string rule;
  enum class Kind { link, operator_stop, monitor } kind = Kind::monitor;
  std::string device;  // link: the device, its symptom and its last good reply
  std::string symptom;
  double since_s = 0.0;
  std::string detail;  // operator_stop, monitor: the rule's words
};

struct TeachInFigures {
  bool taught = false;
  std::uint32_t total_resolution = 0;
  bool encoder_restored = false;
};

// What a run adds to its summary.
struct RunFigures {
  std::vector<LinkFigures> links;
  std::uint64_t cycles = 0;
  std::uint64_t overrun_cycles = 0;
  std::uint64_t missed_deadlines = 0;
  double jitter_p99_us = 0.0;
  double wall_s = 0.0;
  std::string mode;  // hardware, emulated, virtual-time
  int corrections = 0;
  std::optional<TeachInFigures> teach_in;
  std::vector<DeviceVerdict> devices;
  std::optional<EndedBy> ended_by;
};

struct SummaryLine {
  std::string outcome;  // complete, stopped, aborted, unfinished; "not started"
  double duration_s = 0.0;
  std::vector<StepTime> steps;
  std::vector<std::string> faults;  // "4.000s overspeed (category 1): x at 30.0 mm/s", in order
  std::uint64_t journal_dropped = 0;
  std::optional<RunFigures> run;
  std::optional<std::string> not_started;  // why the run never started (a port that did not open)
};

[[nodiscard]] std::string summary_line(const SummaryLine& s);

// The loop's figures as a summary line holds them (a run that ended normally has them).
struct LoopFigures {
  std::uint64_t cycles = 0;
  double jitter_p99_us = 0.0;
  std::uint64_t overrun_cycles = 0;
  std::uint64_t missed_deadlines = 0;
  std::uint64_t journal_dropped = 0;
};

// Seconds, milliseconds kept: 1.27 rather than 1.2700000000000005.
[[nodiscard]] double round_ms(double seconds) noexcept;

}  // namespace cellctl::schema

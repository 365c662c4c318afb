#pragma once
// A run record read back: the journal's lines turned into what the plot, `cellctl report` and
// `cellctl compare` need — the header, the samples, each step as it ran (start, end, held time,
// result), and the marks (faults, injected faults, operator commands, notes) in time order.
// The journal builds one while it writes, from the typed events as their lines record them; the
// commands load one from journal.jsonl through the schema's reader (schema/read_journal_line.hpp):
// one record, whichever way it came.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "journal/event.hpp"
#include "schema/journal_line.hpp"
#include "schema/record_header.hpp"
#include "schema/summary_line.hpp"

namespace cellctl::journal {

using schema::SamplePoint;

struct StepRun {
  int step = 0;  // 1-based, as the run and `cellctl check` number them
  std::string label;
  double start = 0.0;
  double end = 0.0;
  double held_s = 0.0;  // of [start, end], the time the cell was held
  std::string result;   // done, failed, interrupted (a stop or the end came first)
  std::string detail;   // why it failed
  [[nodiscard]] double seconds() const noexcept { return end - start; }
};

enum class MarkKind { fault, injected_fault, fault_cleared, command, note };
[[nodiscard]] std::string_view to_string(MarkKind k) noexcept;

// A stretch of time the cell was held (Holding or Held), until it left for any other state.
struct Hold {
  double from = 0.0;
  double to = 0.0;
};

struct Mark {
  double t = 0.0;
  MarkKind kind = MarkKind::note;
  std::string text;
};

// An injected fault in words, as its line's fields read in order: "scu, silent, scu:silent@2+1, the
// line carries nothing either way" (", still_active=true" before what it does when the run ended first).
[[nodiscard]] std::string describe(const InjectedFault& f);

class RunRecord {
 public:
  // An event as its line records it (its time recorded_time(), a sample's values recorded_value()):
  // what the journal writes, as it writes it. A note whole: add_note().
  void add(const Event& e);
  void add_note(double t, std::string_view text);
  void add_sample(const SamplePoint& s);
  void set_header(schema::RecordHeader h);
  // A line of a kind the record does not know: kept only when it looks like a fault.
  void add_other(double t, std::string_view event, std::string_view description);
  // Steps still open end where the run ended, as interrupted. Called by load(); idempotent.
  void finish();

  // dir/journal.jsonl (or the file itself). Throws std::runtime_error with file:line on a bad line.
  [[nodiscard]] static RunRecord load(const std::filesystem::path& dir_or_file);

  // Each of its fields unset when the record has no header line.
  [[nodiscard]] const schema::RecordHeader& header() const noexcept { return header_; }
  [[nodiscard]] bool has_header() const noexcept { return has_header_; }
  // The summary line's loop figures; none without a summary line or when the run did not end normally.
  [[nodiscard]] const std::optional<schema::LoopFigures>& loop_figures() const noexcept { return loop_; }
  [[nodiscard]] const std::vector<SamplePoint>& samples() const noexcept { return samples_; }
  [[nodiscard]] const std::vector<StepRun>& steps() const noexcept { return steps_; }
  [[nodiscard]] const std::vector<Mark>& marks() const noexcept { return marks_; }
  [[nodiscard]] const std::vector<Hold>& holds() const noexcept { return holds_; }
  [[nodiscard]] const std::string& outcome() const noexcept { return outcome_; }
  [[nodiscard]] double start() const noexcept { return start_; }
  [[nodiscard]] double end() const noexcept { return end_; }
  [[nodiscard]] double duration_s() const noexcept { return end_ - start_; }

  // From the header, or "axis 1"… for a record without one.
  [[nodiscard]] std::vector<std::string> axis_names() const;
  [[nodiscard]] std::optional<std::size_t> measured_axis() const;
  [[nodiscard]] std::string recipe_label() const;  // "demo-drilling 1.0 (recipes/demo.yaml)"
  // The planned time of step n (1-based): a move's profile time (until the planned positions stop
  // changing), a dwell's seconds, 0 for a precondition; nullopt where nothing was planned.
  [[nodiscard]] std::optional<double> planned_s(const StepRun& s) const;
  // The last sample at or before t (the first one if none is).
  [[nodiscard]] const SamplePoint* sample_at(double t) const noexcept;
  // The run was ended by the operator (typed stop/abort, Ctrl-C, SIGTERM) and nothing else failed.
  [[nodiscard]] bool ended_by_operator() const;

 private:
  void close_open_steps(double t, std::string_view result);
  friend class RecordReader;  // load()'s schema::LineReader

  schema::RecordHeader header_;
  bool has_header_ = false;
  std::optional<schema::LoopFigures> loop_;
  std::vector<SamplePoint> samples_;
  std::vector<StepRun> steps_;
  std::vector<Mark> marks_;
  std::vector<Hold> holds_;           // the last one open (to < from) while the cell is held
  std::optional<double> held_since_;  // of the step in progress
  std::string outcome_ = "unfinished";
  double start_ = 0.0;
  double end_ = 0.0;
  bool operator_stop_ = false;  // a stop or abort typed, or Ctrl-C / SIGTERM
  bool other_failure_ = false;  // a fault the operator did not cause, or a failed step
};

}  // namespace cellctl::journal

#pragma once
// A run record read back: the journal's lines turned into what the plot, `cellctl report` and
// `cellctl compare` need — the header, the samples, each step as it ran (start, end, held time,
// result), and the marks (faults, injected faults, operator commands, notes) in time order.
// The journal builds one while it writes (from the very JSON it writes), the commands load one
// from journal.jsonl: one reading of the format.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cellctl::journal {

struct SamplePoint {
  double t = 0.0;
  std::vector<double> planned_mm;  // per axis
  std::vector<double> scu_mm;      // per axis
  double encoder_mm = 0.0;         // of the measured axis, if there is one
  double spindle_set_hz = 0.0;
  double spindle_hz = 0.0;
};

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

struct Mark {
  double t = 0.0;
  MarkKind kind = MarkKind::note;
  std::string text;
};

// What an event says, for kinds without a reader of their own (an injected fault, say): its text
// fields in order, "key=value" for the rest; "t" and "event" left out.
[[nodiscard]] std::string describe_event(const nlohmann::json& line);

class RunRecord {
 public:
  // One journal line (any event; unknown kinds are kept only if they look like faults).
  void add(const nlohmann::json& line);
  // Steps still open end where the run ended, as interrupted. Called by load(); idempotent.
  void finish();

  // dir/journal.jsonl (or the file itself). Throws std::runtime_error with file:line on a bad line.
  [[nodiscard]] static RunRecord load(const std::filesystem::path& dir_or_file);

  [[nodiscard]] const nlohmann::json& header() const noexcept { return header_; }    // {} if none
  [[nodiscard]] const nlohmann::json& summary() const noexcept { return summary_; }  // {} if none
  [[nodiscard]] const std::vector<SamplePoint>& samples() const noexcept { return samples_; }
  [[nodiscard]] const std::vector<StepRun>& steps() const noexcept { return steps_; }
  [[nodiscard]] const std::vector<Mark>& marks() const noexcept { return marks_; }
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

  nlohmann::json header_ = nlohmann::json::object();
  nlohmann::json summary_ = nlohmann::json::object();
  std::vector<SamplePoint> samples_;
  std::vector<StepRun> steps_;
  std::vector<Mark> marks_;
  std::optional<double> held_since_;
  std::string outcome_ = "unfinished";
  double start_ = 0.0;
  double end_ = 0.0;
  bool operator_stop_ = false;  // a stop or abort typed, or Ctrl-C / SIGTERM
  bool other_failure_ = false;  // a fault the operator did not cause, or a failed step
};

}  // namespace cellctl::journal

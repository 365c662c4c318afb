#pragma once
// The fault matrix of issue 9: every device (scu, spindle, encoder) × every kind of rehearsed fault
// (silent, disconnect, corrupt, garbage, a delay below the device's link limit, one above it, the
// device's own error) × what the cell is doing when it comes (idle, axes moving, spindle on). Each
// case is one whole run of a small recipe (tests/faults/recipes/) in virtual time, in this process,
// through the real sessions, emulators and SimLinks, with the fault put in by `--fault`'s machinery
// (runtime::FaultSpec → FaultRehearsal → FaultInjectingLink / the emulator's own fault).
//
// What a case measures, every time from the injection, on the run's clock:
//  - detected: the journal's first monitor fault (its rule and text);
//  - safe: the emulated plant itself — every actuator standing, the spindle motor at 0 Hz — from then
//    on to the end of the run (the truth behind what cellctl says);
//  - ended: the run's end (the journal's summary), and whether it ended by itself;
//  - the journal's summary: closed, naming the injected fault, and its `devices` object (per device
//    `safe` ∈ observed | bounded | unknown, with the evidence).
// What a case expects (bounds per fault class, derived from the cell config with stated margins, and
// the `safe` per device) is in expectation(); verdict() lists every way a run fell short of it. The
// test (fault_matrix_test.cpp) and the table (fault_matrix_table.cpp) use the same verdict.

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "faults/run_truth.hpp"
#include "supervisor/packml.hpp"

namespace cellctl::faults {

enum class FaultClass : std::uint8_t {
  silent,
  disconnect,
  corrupt,
  garbage,
  delay_below,
  delay_above,
  error
};
inline constexpr std::array kFaultClasses = {
    FaultClass::silent,      FaultClass::disconnect,  FaultClass::corrupt, FaultClass::garbage,
    FaultClass::delay_below, FaultClass::delay_above, FaultClass::error};
[[nodiscard]] std::string_view to_string(FaultClass c) noexcept;

enum class Activity : std::uint8_t { idle, moving, spindle_on };
inline constexpr std::array kActivities = {Activity::idle, Activity::moving, Activity::spindle_on};
[[nodiscard]] std::string_view to_string(Activity a) noexcept;

// When the fault comes and how long it lasts, in every case: 1.5 s in, every recipe is in the state
// its name says (the move at full speed, the spindle at 400 Hz); 2 s, as long as the line faults that
// left the spindle turning in the trial — long enough to outlast every detection, short
// enough that a stop re-sent after it gets through.
inline constexpr double kInjectAtS = 1.5;
inline constexpr double kLastingS = 2.0;

struct MatrixCase {
  cell::Device device = cell::Device::scu;
  FaultClass fault = FaultClass::silent;
  Activity activity = Activity::idle;
  double delay_ms = 0.0;  // a delay below the limit: this many ms (0: half the device's limit)
};

// The line latencies a cell meets in service (a USB serial adapter, a busy converter), put on every
// device's replies while the axes move: each is no fault, however long it lasts.
inline constexpr std::array kServiceDelaysMs = {25.0, 50.0, 100.0};
[[nodiscard]] std::vector<MatrixCase> all_cases();
// "scu/silent/idle" ("scu/delay_below=50/moving" with a delay of its own): the table's and the
// test's name of the case.
[[nodiscard]] std::string name_of(const MatrixCase& c);
// The delay a delay class puts on the device's replies: half of the device's link limit below it,
// the limit plus the monitor's link silence above it.
[[nodiscard]] double delay_ms(const MatrixCase& c, const config::CellConfig& cell);
// The --fault text, e.g. "scu:delay=75@1.5+2".
[[nodiscard]] std::string fault_spec_text(const MatrixCase& c, const config::CellConfig& cell);

struct Expectation {
  bool fault_detected = true;  // false: the run completes, no monitor fault at all
  // Noise (garbage) damages most telegrams, not all: a session may ride it out with retries. Then the
  // case is judged as a delay below the limit is (no fault, the recipe completes, every device observed).
  bool may_ride_through = false;
  double detect_ms = 0.0;                // bound from the injection to the first monitor fault
  double safe_ms = 0.0;                  // bound from the injection to the plant at rest
  std::array<Safe, 3> safe{};            // per device (cell::Device order) in the summary …
  std::array<bool, 3> or_observed{};     // … or observed: the line came back before the bound passed
  std::vector<std::string> first_rules;  // the rules the first fault may have; empty: any naming the device
  int exit_status = 1;                   // what `cellctl run` gives for such a run (0, 1 or 5)
  std::string detect_why;                // the detection bound's reasoning, for the table
  std::string why;                       // both bounds' reasoning
};
[[nodiscard]] Expectation expectation(const MatrixCase& c, const config::CellConfig& cell);

struct Outcome {
  bool ended_by_itself = true;        // false: stopped by the harness after kGiveUpS
  std::optional<double> detected_ms;  // first monitor fault after the injection
  std::string first_fault;            // "rule: detail"
  std::string first_rule;
  std::optional<double> safe_ms;  // plant at rest from then to the end (none: not at rest at the end)
  double ended_ms = 0.0;          // the run's end
  supervisor::State final_state = supervisor::State::idle;
  std::string outcome;             // the summary's outcome
  nlohmann::json summary;          // the journal's last line (null: not closed)
  DeviceSafety devices;            // the summary's devices object
  std::optional<int> exit_status;  // as cellctl run would exit (none: the run result cannot say)
  std::string setup_error;         // the run could not be made or threw
};

// Runs one case; its journal goes under `work_dir` (removed unless `keep`).
[[nodiscard]] Outcome run_case(const MatrixCase& c, const config::CellConfig& cell,
                               const std::filesystem::path& work_dir, bool keep = false);

// The exit status of the real `cellctl run RECIPE --virtual-time --fault SPEC` for the case (its
// journal and a copy of the cell config, with the encoder's EEPROM file of its own, under `work_dir`);
// none when it could not be started or did not exit normally.
[[nodiscard]] std::optional<int> cellctl_exit_status(const MatrixCase& c, const config::CellConfig& cell,
                                                     const std::filesystem::path& cellctl,
                                                     const std::filesystem::path& work_dir);

// Every way the outcome falls short of the expectation, in words; empty: the case passes.
[[nodiscard]] std::vector<std::string> verdict(const MatrixCase& c, const Expectation& e, const Outcome& o);

[[nodiscard]] config::CellConfig matrix_cell();  // the shipped config/cell.yaml
[[nodiscard]] std::filesystem::path recipe_of(Activity a);

}  // namespace cellctl::faults

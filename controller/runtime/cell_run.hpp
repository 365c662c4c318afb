#pragma once
// One run of a recipe on the cell: the links for the chosen mode, the emulators where there are any,
// the device sessions, the monitor, the supervisor and the journal, stepped by the control loop.
// In virtual time everything — emulators included — is stepped by the loop on a virtual clock, as
// fast as the machine allows; otherwise the loop runs on the monotonic clock and the emulators (if
// any) on a thread of their own at the loop's real-time priority, behind their links, like real
// devices.

#include <atomic>
#include <bitset>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "cell/cell_state.hpp"
#include "command/arbiter.hpp"
#include "config/cell_config.hpp"
#include "emulation/emulator_setup.hpp"
#include "journal/event_listener.hpp"
#include "journal/event_sink.hpp"
#include "journal/journal.hpp"
#include "link/clock.hpp"
#include "loop/cycle_waiter.hpp"
#include "loop/loop.hpp"
#include "monitor/monitor.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe.hpp"
#include "routines/home_record.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/cell_parts.hpp"
#include "runtime/emulated_cell.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/fault_spec.hpp"
#include "runtime/safe_stop.hpp"
#include "runtime/teach_in_encoder.hpp"
#include "runtime/teach_in_outcome.hpp"
#include "schema/record_header.hpp"
#include "schema/summary_line.hpp"
#include "status/status_view.hpp"
#include "supervisor/supervisor.hpp"

namespace cellctl::runtime {

struct RunOptions {
  RunMode mode = RunMode::emulated;
  std::filesystem::path journal_dir = "runs/latest";
  std::optional<schema::RecordHeader> record_header;  // the journal's first line (journal/record_header.hpp)
  bool trace = false;
  // Who started the run, as its start's reason names them ("start by …"): cellctl serve's jobs are
  // started by the plant or the page.
  std::string start_source = "cellctl run";
  supervisor::SupervisorSettings supervisor;  // mode and sample period are filled in from the config
  // How long after the end a stop is sent again to a device that has not confirmed it and has no
  // protection of its own to bound it (the spindle converter); the SCU is bounded by its own
  // communication time-out and the actuators' stopping time (runtime/safe_stop.hpp).
  double shutdown_timeout_s = 5.0;
  std::vector<FaultSpec> faults;  // to rehearse (emulated and virtual-time runs only)
  // The emulated devices' set-up; read from the cell's file (cell.source) when emulators are needed
  // and none is given here.
  std::optional<emulation::EmulatorSetup> emulators;
  // The folder of the home record (home.json); empty: the cell config's state_dir.
  std::filesystem::path state_dir;
  // The kinds of device the cell may have, in slot order: the registry's, unless a test adds one.
  std::span<const device_seam::DeviceKind> device_kinds = device_seam::cell_device_kinds();
};

struct RunResult {
  supervisor::State final_state = supervisor::State::idle;
  std::string failure;                    // why a step failed, if one did
  std::vector<std::string> faults;        // latched monitor faults, in order
  std::vector<std::string> device_notes;  // sessions' fault reasons, a refused start, an unclosed device
  bool interrupted = false;               // Ctrl-C or SIGTERM ended it
  double duration_s = 0.0;                // of the run, on the run's clock
  double wall_s = 0.0;                    // real time it took
  std::uint64_t cycles = 0;
  std::string loop_summary;
  std::string link_summary;  // per device: replies, worst round trip, longest silence, time-outs
  std::string summary_text;  // the journal's summary for the terminal
  // The safe state each device was left in (nullopt: the cell has no such device).
  Verdicts safety;
  // The fault that ended the run, in words ("scu link: … since 1.502 s"); empty when none did.
  std::string ended_by;
  [[nodiscard]] bool any_unknown() const noexcept {
    for (const auto& s : safety)
      if (s && s->safe == Safe::unknown) return true;
    return false;
  }
  std::string home_record;  // "home record written: <file>" (or why not) when homing changed it
  // How a Teach-In step ended (a Teach-In job): what to write into the config when it is done.
  std::optional<TeachInOutcome> teach_in;
};

class CellRun {
 public:
  // Throws config::ConfigError, link::LinkError, std::invalid_argument (set-up problems: before motion;
  // faults to rehearse on hardware or on a device the cell does not have).
  CellRun(const config::CellConfig& cell, const recipe::Recipe& recipe, RunOptions options);
  ~CellRun();
  CellRun(const CellRun&) = delete;
  CellRun& operator=(const CellRun&) = delete;

  // Starts the recipe and steps the cell until it is Complete, Stopped or Aborted and the devices
  // are closed. `interrupt` (Ctrl-C) is the monitor's operator stop the first time (its category from
  // the config) and an emergency stop the second; `terminate` (SIGTERM) is a controlled stop.
  RunResult run(std::atomic<bool>& interrupt, std::atomic<bool>* terminate = nullptr);

  // An operator command from any thread (the loop's too); carried out at the next cycle and journaled
  // with its source (command::CommandSource::words()). Never waits on the loop: the command is a bit,
  // its source a queued text (should that queue be full, the command still goes, told as "unrecorded").
  void request(supervisor::Command c, std::string_view source = "terminal") noexcept;

  // The port through which the command arbiter reaches this run: its state (from its board, as the
  // last cycle published it) and request().
  [[nodiscard]] command::JobPort port() {
    return {[this] { return board_.read().state; },
            [this](supervisor::Command c, const command::CommandSource& source) {
              request(c, source.words());
              return command::Taken{command::Taken::How::by_run, {}};
            }};
  }

  // Text the operator typed that is no command, or a command that was never judged (a retained
  // message): journaled at the next cycle, whole (in parts of a journal::Note; the caller waits while
  // the loop has not taken the earlier ones). Any thread, one at a time.
  void note_from_operator(std::string_view text) noexcept {
    const std::lock_guard lock(note_mutex_);
    NoteQueueWriter w{operator_notes_, loop_stop_};
    journal::NoteWriter notes(w, 0.0);
    for (const char c : text) notes.put(c);
  }
  // Hears every event as the journal records it, on the journal's thread (journal::Journal::listen);
  // nullptr: nobody. Taken away (nullptr) before the listener goes.
  void listen(journal::EventListener* listener) { journal_.listen(listener); }
  // A manual Teach-In step: the operator has moved the axis as its prompt asked (any thread).
  void confirm() noexcept { confirm_.store(true); }

  // Tests in virtual time: called at the start of every cycle, on the loop's thread.
  void on_cycle(std::function<void(double t, CellRun&)> hook) { hook_ = std::move(hook); }

  [[nodiscard]] EmulatedCell* emulators() noexcept { return parts_.emulated.get(); }
  [[nodiscard]] const cell::CellState& state() const noexcept { return state_; }
  [[nodiscard]] const supervisor::Supervisor& supervisor() const noexcept { return *supervisor_; }
  [[nodiscard]] const monitor::Monitor& monitor() const noexcept { return monitor_; }
  [[nodiscard]] const status::StatusBoard& status() const noexcept { return board_; }
  [[nodiscard]] const CellLinks& links() const noexcept { return *parts_.links; }
  [[nodiscard]] const loop::Loop& loop() const noexcept { return *loop_; }
  [[nodiscard]] std::vector<std::string> realtime_warnings() const { return realtime_warnings_; }
  [[nodiscard]] const std::filesystem::path& home_record_file() const noexcept { return home_record_file_; }
  [[nodiscard]] const routines::HomeRecord& home_record() const noexcept { return home_record_; }

 private:
  void cycle(link::TimePoint now, std::atomic<bool>& interrupt);
  void take_commands(double t, std::atomic<bool>& interrupt);
  // Reset and clear: the devices clear their own faults, the monitor judges its latches, then the
  // supervisor takes the command (where the run has ended) or the latches alone are cleared.
  void judge_reset(double t, supervisor::Command c, const journal::Text& source);
  void report_devices(double t, RunResult& r);
  // The safe state each device was left in and what ended the run, for the caller and the summary.
  void report_safety(RunResult& r, schema::RunFigures& figures) const;
  [[nodiscard]] static constexpr unsigned bit(supervisor::Command c) noexcept {
    return 1u << static_cast<unsigned>(c);
  }
  void publish_status(double t);
  // The words of the monitor's first active latch (what a demanded stop is for), empty with none.
  [[nodiscard]] std::string_view first_active_detail() const noexcept;
  void run_emulator_thread();
  void save_home_record(double t, std::int64_t unix_start, RunResult& r);

  const config::CellConfig& cell_;
  const recipe::Recipe& recipe_;
  recipe::Program program_;
  RunOptions options_;
  std::filesystem::path home_record_file_;
  routines::HomeRecord home_record_;  // what `require: homed` checks; `home` steps update it
  std::string home_record_problem_;   // the file on disk did not parse

  link::MonotonicClock real_clock_;
  link::VirtualClock virtual_clock_;
  const link::Clock& clock_;
  CellParts parts_;  // the cycle waiter, faults rehearsed, links, emulators, device sessions
  std::unique_ptr<SafeStop> safe_stop_;
  // The encoder's Teach-In port, for a program with a Teach-In step (nullptr otherwise).
  std::unique_ptr<TeachInEncoder> teach_in_encoder_;
  std::atomic<bool> confirm_{false};
  journal::Journal journal_;
  monitor::Monitor monitor_;
  std::unique_ptr<supervisor::Supervisor> supervisor_;
  std::unique_ptr<loop::Loop> loop_;

  cell::CellState state_;
  status::StatusBoard board_;
  std::atomic<unsigned> requested_{0};  // one bit per supervisor::Command
  struct Requested {
    supervisor::Command command;
    journal::Text source;
  };
  std::mutex request_mutex_;                        // the writers of request_sources_ (one at a time)
  wire::SpscQueue<Requested, 16> request_sources_;  // the loop reads it without the lock
  std::array<journal::Text, supervisor::kCommands> sources_{};  // the loop's: each command's last source
  std::mutex note_mutex_;                                       // the writers of operator_notes_
  wire::SpscQueue<journal::Note, 64> operator_notes_;
  // Feeds a note's parts into operator_notes_, waiting for room (not once the loop has ended).
  struct NoteQueueWriter final : journal::EventSink {
    NoteQueueWriter(wire::SpscQueue<journal::Note, 64>& q, const std::atomic<bool>& stop)
        : queue(q), stopped(stop) {}
    void post(double, const journal::Payload& p) noexcept override {
      const auto& note = std::get<journal::Note>(p);
      while (!queue.push(note) && !stopped.load()) std::this_thread::yield();
    }
    wire::SpscQueue<journal::Note, 64>& queue;
    const std::atomic<bool>& stopped;
  };
  std::atomic<bool>* terminate_ = nullptr;
  bool terminated_ = false;  // SIGTERM seen: its stop requested
  bool interrupted_ = false;
  link::TimePoint start_{};
  std::function<void(double, CellRun&)> hook_;
  std::atomic<bool> emulators_stop_{false};
  std::thread emulator_thread_;
  std::vector<std::string> realtime_warnings_;
  bool operator_stop_ = false;   // Ctrl-C once: the monitor's operator stop
  bool emergency_stop_ = false;  // Ctrl-C twice: the monitor's emergency stop
  std::optional<link::TimePoint> shutdown_since_;
  // The monitor fault that ended the run, when one did: the first since the last reset, or a later
  // one that demanded a stronger stop.
  struct FirstFault {
    monitor::Rule rule;
    config::StopCategory category;  // the stop it demanded
    double t;
    journal::Text detail;
    std::optional<std::size_t> link;  // the slot of a device link that had failed then: named after it
    double link_since = 0.0;          // its last good reply, s from the start
  };
  [[nodiscard]] FirstFault first_fault(monitor::Rule rule, config::StopCategory category, double t,
                                       const journal::Text& detail) const noexcept;
  std::optional<FirstFault> first_fault_;
  std::atomic<bool> loop_stop_{false};
};

}  // namespace cellctl::runtime

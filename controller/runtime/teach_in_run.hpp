#pragma once
// One Teach-In on the cell (cellctl teach-in): the links for the chosen mode, the emulators where
// there are any, the device sessions, the monitor and the routines::TeachIn state machine, stepped
// by the control loop — in virtual time as fast as the machine allows, or in real time against the
// ports (emulated ones behind pseudo-terminals, on a thread of their own), as `cellctl run` does.
// The journal records the phases, faults and injected faults. The config file is not touched here:
// the caller writes the result once the routine has verified it.

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "journal/journal.hpp"
#include "link/clock.hpp"
#include "loop/cycle_waiter.hpp"
#include "loop/loop.hpp"
#include "monitor/monitor.hpp"
#include "routines/teach_in.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/cell_parts.hpp"
#include "runtime/emulated_cell.hpp"
#include "runtime/emulator_setup.hpp"
#include "runtime/fault_rehearsal.hpp"
#include "runtime/fault_spec.hpp"
#include "runtime/teach_in_encoder.hpp"

namespace cellctl::runtime {

struct TeachInRunOptions {
  RunMode mode = RunMode::emulated;
  std::filesystem::path journal_dir = "runs/teach-in";
  nlohmann::json record_header;
  bool trace = false;
  std::vector<FaultSpec> faults;  // emulated and virtual-time only
  std::optional<EmulatorSetup> emulators;
  double shutdown_timeout_s = 5.0;
};

struct TeachInProgress {
  double t = 0.0;
  routines::TeachInPhase phase = routines::TeachInPhase::checking;
  double scu_mm = 0.0;
  double encoder_mm = 0.0;
  std::string prompt;  // manual mode: what the operator should do now
};

struct TeachInOutcome {
  bool done = false;
  routines::TeachInResult result;
  std::string failure;
  bool restored = true;           // false: the encoder's configured parameters could not be confirmed
  bool interrupted = false;       // its interrupt was set: Ctrl-C, or a stop from the plant or page (serve)
  encoder::SessionConfig taught;  // the settings to record (when done)
  double units_per_mm = 0.0;
  std::vector<std::string> device_notes;
};

class TeachInRun {
 public:
  // Throws config::ConfigError, link::LinkError, std::invalid_argument (set-up: before motion).
  TeachInRun(const config::CellConfig& cell, const routines::TeachInRequest& request,
             TeachInRunOptions options);
  ~TeachInRun();
  TeachInRun(const TeachInRun&) = delete;
  TeachInRun& operator=(const TeachInRun&) = delete;

  // Runs until the routine is done or failed and the devices are closed. `interrupt` (Ctrl-C) aborts.
  // `progress` is called on the loop's thread at each phase change and every 0.5 s.
  TeachInOutcome run(std::atomic<bool>& interrupt,
                     const std::function<void(const TeachInProgress&)>& progress = {});
  // Every journal line as it is written, on the journal's thread (journal::Journal::on_line).
  void on_journal_line(std::function<void(const nlohmann::json&)> listener) {
    journal_.on_line(std::move(listener));
  }
  // Manual mode: the operator did what the prompt asked (any thread).
  void confirm() noexcept { confirm_.store(true); }

  // Tests: called at the start of every cycle, on the loop's thread.
  void on_cycle(std::function<void(double t, TeachInRun&)> hook) { hook_ = std::move(hook); }
  [[nodiscard]] EmulatedCell* emulators() noexcept { return parts_.emulated.get(); }
  [[nodiscard]] const routines::TeachIn& routine() const noexcept { return *routine_; }
  [[nodiscard]] const cell::CellState& state() const noexcept { return state_; }

 private:
  void cycle(link::TimePoint now, std::atomic<bool>& interrupt,
             const std::function<void(const TeachInProgress&)>& progress);

  const config::CellConfig& cell_;
  TeachInRunOptions options_;
  link::MonotonicClock real_clock_;
  link::VirtualClock virtual_clock_;
  const link::Clock& clock_;
  CellParts parts_;  // the cycle waiter, faults rehearsed, links, emulators, device sessions
  std::unique_ptr<TeachInEncoder> encoder_;
  journal::Journal journal_;
  monitor::Monitor monitor_;
  std::unique_ptr<routines::TeachIn> routine_;
  std::unique_ptr<loop::Loop> loop_;
  cell::CellState state_;
  link::TimePoint start_{};
  std::function<void(double, TeachInRun&)> hook_;
  std::atomic<bool> confirm_{false};
  std::atomic<bool> emulators_stop_{false};
  std::thread emulator_thread_;
  std::optional<link::TimePoint> shutdown_since_;
  std::atomic<bool> loop_stop_{false};
  bool interrupted_ = false;
  routines::TeachInPhase last_phase_ = routines::TeachInPhase::checking;
  double next_progress_t_ = 0.0;
};

}  // namespace cellctl::runtime

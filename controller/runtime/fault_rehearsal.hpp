#pragma once
// Faults put into an emulated run on purpose (cellctl run --fault), at the times the operator gave, so
// that a process engineer sees what the cell does before it happens for real: line faults through a
// link::FaultInjectingLink on the session's end of the device's link, the device's own error through
// its emulator's fault hooks, and each fault's start and end in the journal.
//
// The device's own error is its emulator's (emulation::EmulatedDevice::set_own_error), as its manual
// describes it and its kind (device_seam/device_registry.hpp) says in words:
//  - SCU: a lasting actuator fault on every actuator (error code bits 15..20: the actuator is fast-
//    stopped; the bit is reset with the next motion and, while the fault lasts, set again at once).
//    The manual has no error reply for an actuator fault — CSE/PDE/PCE/ICE/PE answer telegram and
//    permission errors — so the fault shows where the manual puts it: in the error code and status.
//  - spindle converter: the motor's over-temperature (PTC): fault 31 latched in statusout, the motor
//    runs down, and only once the fault has ended can CMD System Reset clear it.
//  - encoder: the position error alarm in its extended diagnosis (octet 8 bit 0, announced by DH).
//
// Threads: start() before the loop and the emulator thread begin; drive_emulators() on the thread
// that polls the emulators; post_journal() on the loop's thread. No allocation after start().

#include <array>
#include <bitset>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "journal/event_sink.hpp"
#include "link/clock.hpp"
#include "link/fault_injecting_link.hpp"
#include "runtime/emulated_cell.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::runtime {

// The fault-injecting link on each device's line (nullptr: no line fault for that device).
using FaultLinks = std::array<link::FaultInjectingLink*, cell::kMaxDevices>;

class FaultRehearsal {
 public:
  // Throws std::invalid_argument with problem()'s text.
  FaultRehearsal(std::vector<FaultSpec> faults, const config::CellConfig& cell,
                 std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());

  // Why these faults cannot be rehearsed on this cell (a device it does not have, too many line faults
  // for one device), or nullopt.
  [[nodiscard]] static std::optional<std::string> problem(
      const std::vector<FaultSpec>& faults, const config::CellConfig& cell,
      std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());

  // The devices (by slot) whose line needs a FaultInjectingLink.
  [[nodiscard]] std::bitset<cell::kMaxDevices> lines() const noexcept;
  [[nodiscard]] const std::vector<FaultSpec>& faults() const noexcept { return faults_; }

  // The run starts: each line fault is scheduled on its device's link, from `start` on.
  void start(link::TimePoint start, const FaultLinks& links);
  // Turns the devices' own errors on and off as their windows open and close.
  void drive_emulators(link::TimePoint now, EmulatedCell& emulators);
  // Posts a fault_injected / fault_injection_ended event for every window that opened or closed.
  void post_journal(link::TimePoint now, double t, journal::EventSink& journal);
  // The run has ended: a fault still in place ends with it (still_active), one whose time never came
  // is said to have not been injected.
  void post_run_end(double t, journal::EventSink& journal);

  // What a fault does, in words (static text; "?" for a device none of `kinds` is).
  [[nodiscard]] static std::string_view what(
      const FaultSpec& f,
      std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds()) noexcept;

 private:
  [[nodiscard]] bool open_at(std::size_t i, link::TimePoint now) const noexcept;
  [[nodiscard]] bool over_at(std::size_t i, link::TimePoint now) const noexcept;

  std::span<const device_seam::DeviceKind> kinds_;
  std::vector<FaultSpec> faults_;
  std::vector<std::size_t> slots_;  // each fault's device
  link::TimePoint start_{};
  std::vector<bool> began_, ended_;                        // loop side
  std::array<bool, cell::kMaxDevices> device_error_on_{};  // emulator side
};

}  // namespace cellctl::runtime

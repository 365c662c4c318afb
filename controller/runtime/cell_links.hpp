#pragma once
// The byte links of a run, by mode: in virtual time every device is an emulator on a SimLink; in an
// emulated run every device is an emulator in this process on a SocketPair (no tty layer: a pty's
// bytes wait for a normal-priority kernel worker that a loaded machine starves — socket_pair.hpp);
// on hardware each device's configured port is opened, and a device whose port is "emulated" gets
// its emulator on a SocketPair too. A device named in
// `fault_lines` gets a FaultInjectingLink on the session's end, for a fault rehearsal (below the
// trace, so the trace shows what the session sent and received).

#include <array>
#include <bitset>
#include <memory>
#include <string>
#include <vector>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "link/clock.hpp"
#include "link/fault_injecting_link.hpp"
#include "link/serial_link.hpp"
#include "link/sim_link.hpp"
#include "link/socket_pair.hpp"
#include "link/tracing_link.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/emulated_cell.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::runtime {

enum class RunMode { hardware, emulated, virtual_time };
[[nodiscard]] constexpr const char* to_string(RunMode m) noexcept {
  return m == RunMode::hardware ? "hardware" : m == RunMode::emulated ? "emulated" : "virtual-time";
}
// A writer (the run record, the trace) that falls behind: a virtual-time run waits for it (its time
// costs nothing), a real-time loop never waits on it — it drops and counts.
[[nodiscard]] constexpr wire::WhenFull when_writer_full(RunMode m) noexcept {
  return m == RunMode::virtual_time ? wire::WhenFull::wait : wire::WhenFull::drop_and_count;
}
// The clock a run goes by: the virtual one the loop steps in virtual time, else the real one.
[[nodiscard]] inline const link::Clock& run_clock(RunMode m, const link::MonotonicClock& real,
                                                  const link::VirtualClock& virtual_clock) noexcept {
  return m == RunMode::virtual_time ? static_cast<const link::Clock&>(virtual_clock)
                                    : static_cast<const link::Clock&>(real);
}

class CellLinks {
 public:
  // Throws link::LinkError naming the port when one cannot be opened.
  CellLinks(const config::CellConfig& cell, RunMode mode, const link::Clock& clock, bool trace,
            std::bitset<cell::kDevices> fault_lines = {});

  [[nodiscard]] DeviceLinks master() const noexcept { return master_; }
  [[nodiscard]] DeviceLinks device() const noexcept { return device_; }
  // The fault-injecting link of each device (nullptr where `fault_lines` did not name it).
  [[nodiscard]] const std::array<link::FaultInjectingLink*, cell::kDevices>& fault_links() const noexcept {
    return fault_links_;
  }
  // Opens a device's port again after it was lost (link::Link::reopen through the fault-injecting
  // and tracing links): ok() when the session may use its link again. For the safe-stop only.
  link::IoResult reopen(cell::Device device);
  [[nodiscard]] bool any_emulated() const noexcept {
    return device_.scu || device_.spindle || device_.encoder;
  }
  // --trace times count from the run's start (as the journal's do) and tell the wall clock.
  void start_trace_clock(link::TimePoint run_start) noexcept { sink_.start_clock(run_start); }
  // "scu: /dev/ttyUSB0 (38400 8N1)", one line per device, for the operator.
  [[nodiscard]] std::vector<std::string> describe() const;

 private:
  link::Link* open(cell::Device device, const config::PortConfig& port, link::Link*& device_side);

  const link::Clock& clock_;
  RunMode mode_;
  bool trace_;
  std::bitset<cell::kDevices> fault_lines_;
  std::array<link::FaultInjectingLink*, cell::kDevices> fault_links_{};
  link::LogTraceSink sink_;  // in virtual time it waits for its writer: nothing real-time to protect
  std::vector<std::unique_ptr<link::SimLink>> sims_;
  std::vector<std::unique_ptr<link::SocketPair>> socket_pairs_;
  std::vector<std::unique_ptr<link::Link>> owned_;
  std::vector<std::string> descriptions_;
  DeviceLinks master_;
  DeviceLinks device_;
};

}  // namespace cellctl::runtime

#pragma once
// The byte links of a run, by mode: in virtual time every device is an emulator on a SimLink; in an
// emulated run every device is an emulator in this process on a SocketPair (no tty layer: a pty's
// bytes wait for a normal-priority kernel worker that a loaded machine starves — socket_pair.hpp);
// on hardware each device's configured port is opened, and a device whose port is "emulated" gets
// its emulator on a SocketPair too. A line for every kind of device (device_seam/device_registry.hpp)
// whose port the cell's config names, in its slot. A device named in
// `fault_lines` gets a FaultInjectingLink on the session's end, for a fault rehearsal (below the
// trace, so the trace shows what the session sent and received).

#include <algorithm>
#include <array>
#include <bitset>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "link/clock.hpp"
#include "link/fault_injecting_link.hpp"
#include "link/serial_link.hpp"
#include "link/sim_link.hpp"
#include "link/socket_pair.hpp"
#include "link/tracing_link.hpp"
#include "runtime/device_links.hpp"
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
            std::bitset<cell::kMaxDevices> fault_lines = {},
            std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());

  [[nodiscard]] const DeviceLinks& master() const noexcept { return master_; }
  [[nodiscard]] const DeviceLinks& device() const noexcept { return device_; }
  // The fault-injecting link of each device (nullptr where `fault_lines` did not name it).
  [[nodiscard]] const std::array<link::FaultInjectingLink*, cell::kMaxDevices>& fault_links() const noexcept {
    return fault_links_;
  }
  // Opens a device's port again after it was lost (link::Link::reopen through the fault-injecting
  // and tracing links): ok() when the session may use its link again. For the safe-stop only.
  link::IoResult reopen(std::size_t slot);
  [[nodiscard]] bool any_emulated() const noexcept {
    return std::any_of(device_.begin(), device_.end(), [](const auto* l) { return l != nullptr; });
  }
  // --trace times count from the run's start (as the journal's do) and tell the wall clock.
  void start_trace_clock(link::TimePoint run_start) noexcept { sink_.start_clock(run_start); }
  // "scu: /dev/ttyUSB0 (38400 8N1)", one line per device, for the operator.
  [[nodiscard]] std::vector<std::string> describe() const;

 private:
  link::Link* open(std::size_t slot, std::string_view name, const config::PortConfig& port);

  const link::Clock& clock_;
  RunMode mode_;
  bool trace_;
  std::bitset<cell::kMaxDevices> fault_lines_;
  std::array<link::FaultInjectingLink*, cell::kMaxDevices> fault_links_{};
  link::LogTraceSink sink_;  // in virtual time it waits for its writer: nothing real-time to protect
  std::vector<std::unique_ptr<link::SimLink>> sims_;
  std::vector<std::unique_ptr<link::SocketPair>> socket_pairs_;
  std::vector<std::unique_ptr<link::Link>> owned_;
  std::vector<std::string> descriptions_;
  DeviceLinks master_{};
  DeviceLinks device_{};
};

}  // namespace cellctl::runtime

#include "runtime/cell_parts.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "journal/record_header.hpp"

namespace cellctl::runtime {

CellParts open_cell_parts(const config::CellConfig& cell, RunMode mode, const link::Clock& clock,
                          link::VirtualClock& virtual_clock, bool trace, const std::vector<FaultSpec>& faults,
                          std::optional<emulation::EmulatorSetup>& emulators,
                          std::span<const device_seam::DeviceKind> kinds) {
  CellParts p;
  if (mode == RunMode::virtual_time)
    p.waiter = std::make_unique<loop::VirtualWaiter>(virtual_clock);
  else
    p.waiter = std::make_unique<loop::MonotonicWaiter>();
  if (!faults.empty()) {
    if (mode == RunMode::hardware)
      throw std::invalid_argument("faults are rehearsed on emulators only (--emulate or --virtual-time)");
    p.rehearsal = std::make_unique<FaultRehearsal>(faults, cell, kinds);
  }
  p.links = std::make_unique<CellLinks>(
      cell, mode, clock, trace, p.rehearsal ? p.rehearsal->lines() : std::bitset<cell::kMaxDevices>{}, kinds);
  if (p.links->any_emulated()) {
    if (!emulators) emulators = emulation::load_emulator_setup(cell);
    p.emulated = std::make_unique<EmulatedCell>(cell, *emulators, p.links->device(), kinds);
  }
  const auto master = p.links->master();
  p.devices = std::make_unique<CellDevices>(
      cell, master, [links = p.links.get()](std::size_t slot) { return links->reopen(slot).ok(); }, kinds);
  return p;
}

std::string config_sha256(const config::CellConfig& cell) {
  try {
    return journal::file_sha256(cell.source);
  } catch (const std::exception&) {
    return {};  // a cell made in memory (tests): no file to hash
  }
}

void serve_emulators(const std::atomic<bool>& stop, const link::Clock& clock, FaultRehearsal* rehearsal,
                     EmulatedCell& emulated) {
  while (!stop.load()) {
    const auto now = clock.now();
    if (rehearsal) rehearsal->drive_emulators(now, emulated);
    emulated.poll(now);
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

}  // namespace cellctl::runtime

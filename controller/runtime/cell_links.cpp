#include "runtime/cell_links.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "link/link_error.hpp"

namespace cellctl::runtime {

namespace {
// An open failure names the device first: with three ports, a path alone does not say which is missing.
std::unique_ptr<link::SerialLink> open_serial(const std::string& device, const std::string& path,
                                              const link::LineFormat& line) {
  try {
    return link::SerialLink::open(path, line);
  } catch (const link::LinkError& e) {
    throw link::LinkError(fmt::format("{}: {}", device, e.what()), e.cause());
  }
}
}  // namespace

CellLinks::CellLinks(const config::CellConfig& cell, RunMode mode, const link::Clock& clock, bool trace,
                     std::bitset<cell::kMaxDevices> fault_lines,
                     std::span<const device_seam::DeviceKind> kinds)
    : clock_(clock), mode_(mode), trace_(trace), fault_lines_(fault_lines), sink_(when_writer_full(mode)) {
  if (kinds.size() > cell::kMaxDevices) throw std::invalid_argument("more devices than a cell has slots for");
  for (std::size_t slot = 0; slot < kinds.size(); ++slot)
    if (const auto port = kinds[slot].port(cell)) master_[slot] = open(slot, kinds[slot].name, *port);
}

link::Link* CellLinks::open(std::size_t slot, std::string_view device_name, const config::PortConfig& port) {
  const std::string name(device_name);
  link::Link*& device_side = device_[slot];
  link::Link* master = nullptr;
  if (mode_ == RunMode::virtual_time) {
    auto& sim = *sims_.emplace_back(std::make_unique<link::SimLink>(clock_, port.line, name));
    master = &sim.master();
    device_side = &sim.device();
    descriptions_.push_back(
        fmt::format("{}: emulator on a simulated {} line (virtual time)", name, port.line.describe()));
  } else if (mode_ == RunMode::emulated || port.emulated()) {
    // Our own line (not the published pty: `cellctl emulate` may be running beside us), and no tty:
    // a socket delivers at write() what a pty leaves to a kernel worker the load can starve.
    auto& pair = *socket_pairs_.emplace_back(std::make_unique<link::SocketPair>(name));
    device_side = &pair.device();
    master = &pair.master();
    descriptions_.push_back(fmt::format("{}: emulator in this process, over a socket pair", name));
  } else {
    master = owned_.emplace_back(open_serial(name, port.port, port.line)).get();
    descriptions_.push_back(fmt::format("{}: {}", name, master->describe()));
  }
  if (fault_lines_.test(slot)) {
    // Seeded per device: the same rehearsal corrupts the same bits every time.
    auto faulty =
        std::make_unique<link::FaultInjectingLink>(*master, clock_, static_cast<std::uint32_t>(slot + 1));
    fault_links_[slot] = faulty.get();
    master = owned_.emplace_back(std::move(faulty)).get();
  }
  if (trace_)
    master = owned_.emplace_back(std::make_unique<link::TracingLink>(*master, clock_, sink_, name)).get();
  return master;
}

link::IoResult CellLinks::reopen(std::size_t slot) {
  link::Link* l = slot < master_.size() ? master_[slot] : nullptr;
  if (l == nullptr) return {0, link::IoStatus::failed, 0};
  return l->reopen();
}

std::vector<std::string> CellLinks::describe() const {
  return descriptions_;
}

}  // namespace cellctl::runtime

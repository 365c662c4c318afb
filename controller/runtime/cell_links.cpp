#include "runtime/cell_links.hpp"

#include <fmt/format.h>

namespace cellctl::runtime {

CellLinks::CellLinks(const config::CellConfig& cell, RunMode mode, const link::Clock& clock, bool trace)
    : clock_(clock),
      mode_(mode),
      trace_(trace),
      sink_(mode == RunMode::virtual_time ? wire::WhenFull::wait : wire::WhenFull::drop_and_count) {
  if (cell.scu) master_.scu = open("scu", cell.scu->port, device_.scu);
  if (cell.spindle) master_.spindle = open("spindle", cell.spindle->port, device_.spindle);
  if (cell.encoder) master_.encoder = open("encoder", cell.encoder->port, device_.encoder);
}

link::Link* CellLinks::open(const std::string& name, const config::PortConfig& port,
                            link::Link*& device_side) {
  link::Link* master = nullptr;
  if (mode_ == RunMode::virtual_time) {
    auto& sim = *sims_.emplace_back(std::make_unique<link::SimLink>(clock_, port.line, name));
    master = &sim.master();
    device_side = &sim.device();
    descriptions_.push_back(
        fmt::format("{}: emulator on a simulated {} line (virtual time)", name, port.line.describe()));
  } else if (mode_ == RunMode::emulated || port.emulated()) {
    // A pty of our own (not the published one: `cellctl emulate` may be running beside us).
    auto& pty = *ptys_.emplace_back(std::make_unique<link::PtyPair>(name));
    device_side = &pty.device();
    master = owned_.emplace_back(link::SerialLink::open(pty.peer_path(), port.line)).get();
    descriptions_.push_back(fmt::format("{}: emulator on pseudo-terminal {}", name, pty.peer_path()));
  } else {
    master = owned_.emplace_back(link::SerialLink::open(port.port, port.line)).get();
    descriptions_.push_back(fmt::format("{}: {}", name, master->describe()));
  }
  if (trace_)
    master = owned_.emplace_back(std::make_unique<link::TracingLink>(*master, clock_, sink_, name)).get();
  return master;
}

std::vector<std::string> CellLinks::describe() const {
  return descriptions_;
}

}  // namespace cellctl::runtime

#include "runtime/cell_devices.hpp"

#include <stdexcept>

namespace cellctl::runtime {
namespace {

cell::LinkState link_state(const link::DeviceSession& s, link::TimePoint now) {
  const auto& h = s.health();
  return {.active = s.lifecycle() == link::Lifecycle::active,
          .fault = s.lifecycle() == link::Lifecycle::fault,
          .silent_for = s.silent_for(now),
          .counts = {.good_replies = h.good_replies,
                     .timeouts = h.timeouts,
                     .bad_frames = h.bad_frames,
                     .refusals = h.error_replies}};
}

}  // namespace

CellDevices::CellDevices(const config::CellConfig& cell, std::span<link::Link* const> links, Reopen reopen,
                         std::span<const device_seam::DeviceKind> kinds)
    : axis_count_(static_cast<std::uint8_t>(cell.axes.size())) {
  if (kinds.size() > cell::kMaxDevices) throw std::invalid_argument("more devices than a cell has slots for");
  for (std::size_t slot = 0; slot < links.size(); ++slot) {
    if (!links[slot]) continue;
    if (slot >= kinds.size()) throw std::invalid_argument("a link in a slot no kind of device has");
    auto device =
        kinds[slot].make(slot, cell, *links[slot], [reopen, slot] { return reopen && reopen(slot); });
    if (!device) continue;
    present_.push_back(device.get());
    owned_.push_back(std::move(device));
  }
  // The three the cell knows by type, for what only they do (the Teach-In's encoder, the CLI's views).
  for (auto* d : present_) {
    if (auto* s = dynamic_cast<device_seam::ScuDevice*>(d)) scu_ = s;
    if (auto* s = dynamic_cast<device_seam::SpindleDevice*>(d)) spindle_ = s;
    if (auto* s = dynamic_cast<device_seam::EncoderDevice*>(d)) encoder_ = s;
  }
}

void CellDevices::activate(link::TimePoint now) {
  for (auto* d : present_) d->session().activate(now);
}

void CellDevices::receive(link::TimePoint now) {
  for (auto* d : present_) d->session().receive(now);
}

void CellDevices::transmit(link::TimePoint now) {
  for (auto* d : present_) d->session().transmit(now);
}

void CellDevices::read(link::TimePoint now, cell::CellState& out) {
  out.now = now;
  out.axis_count = axis_count_;
  for (auto& l : out.links)
    l = {.active = true, .fault = false, .silent_for = {}, .counts = {}};  // absent devices: no rule
  out.devices = {};
  for (auto* d : present_) {
    out.links[d->slot()] = link_state(d->session(), now);
    out.devices[d->slot()] = d->name();
    d->read(now, out);
  }
}

void CellDevices::apply(const cell::Intents& in) {
  for (auto* d : present_) d->apply(in);
}

}  // namespace cellctl::runtime

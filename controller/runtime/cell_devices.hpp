#pragma once
// The cell's devices seen as one cell: each device above its session (device_seam::CellDevice) fills its
// slot of the CellState and turns changes of its part of the supervisor's Intents into session
// commands; this class makes them from the registry (device_seam/device_registry.hpp) and iterates
// them. It decodes nothing itself. Each cycle: receive(now) → read(now, state) → … → apply(intents) →
// transmit(now), so a command decided in cycle k goes out in cycle k. Non-blocking and allocation-free
// per cycle.

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_config.hpp"
#include "device_seam/cell_device.hpp"
#include "device_seam/device_registry.hpp"
#include "device_seam/encoder_device.hpp"
#include "device_seam/scu_device.hpp"
#include "device_seam/spindle_device.hpp"
#include "link/device_session.hpp"
#include "link/link.hpp"

namespace cellctl::runtime {

class CellDevices {
 public:
  // Opens a device's port again after it was lost (by slot): true when its session may use it again.
  using Reopen = std::function<bool(std::size_t slot)>;

  // The cell's devices of `kinds` (the registry's, unless a test adds its own), each on its link in
  // `links` (by slot; nullptr: the cell has no such device). Throws std::invalid_argument (a session's
  // config) — at construction only.
  CellDevices(const config::CellConfig& cell, std::span<link::Link* const> links, Reopen reopen,
              std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());

  void activate(link::TimePoint now);
  void receive(link::TimePoint now);
  void transmit(link::TimePoint now);

  // The snapshot of the cell now (after receive()).
  void read(link::TimePoint now, cell::CellState& out);
  // Hands what changed in `intents` to the devices (before transmit()).
  void apply(const cell::Intents& intents);

  // The devices the cell has, in slot order.
  [[nodiscard]] std::span<device_seam::CellDevice* const> devices() const noexcept { return present_; }
  [[nodiscard]] scu::Session* scu() noexcept { return scu_ ? &scu_->scu() : nullptr; }
  [[nodiscard]] spindle::Session* spindle() noexcept { return spindle_ ? &spindle_->spindle() : nullptr; }
  [[nodiscard]] encoder::Session* encoder() noexcept { return encoder_ ? &encoder_->encoder() : nullptr; }

 private:
  std::uint8_t axis_count_;
  std::vector<std::unique_ptr<device_seam::CellDevice>> owned_;
  std::vector<device_seam::CellDevice*> present_;
  device_seam::ScuDevice* scu_ = nullptr;
  device_seam::SpindleDevice* spindle_ = nullptr;
  device_seam::EncoderDevice* encoder_ = nullptr;
};

}  // namespace cellctl::runtime

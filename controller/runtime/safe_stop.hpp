#pragma once
// The safe-stop at the end of a run: every device is brought to rest and stays watched until its rest
// is confirmed by the device (observed) or a stated bound has passed after which the device's own
// protection has surely acted (bounded); what is neither is unknown and said loudly. The loop keeps
// cycling (receive … transmit) until every device is resolved, so cellctl never exits before.
//
// How each device is stopped, what confirms its rest and its own bounds are the device's policy
// (device_seam::CellDevice: begin_stop, step_stop, evidence — the SCU's, the spindle converter's and
// the encoder's in device_seam/); this class runs them all: it tells each what the run is at (begun,
// whether whatever drives the axes is resolved) and collects the verdicts.
//
// observe() every cycle of the run and step() every cycle from begin() on allocate nothing; the
// verdicts' words are composed after the loop.

#include <array>
#include <optional>
#include <string>

#include "cell/cell_state.hpp"
#include "device_seam/device_safety.hpp"
#include "link/clock.hpp"
#include "runtime/cell_devices.hpp"

namespace cellctl::runtime {

using device_seam::DeviceSafety;
using device_seam::Safe;
using device_seam::to_string;

// Per device slot; nullopt for a slot without a device.
using Verdicts = std::array<std::optional<DeviceSafety>, cell::kMaxDevices>;

class SafeStop {
 public:
  // `confirm_within`: how long after begin() a stop is sent again for a device without a bound of its
  // own (the spindle). `start`: the run's start, for the times in the evidence.
  SafeStop(CellDevices& devices, link::Duration confirm_within, link::TimePoint start);

  // Every cycle of the run, after the cell state was read: what the devices last said.
  void observe(link::TimePoint now, const cell::CellState& state) noexcept;
  // The run is over: the orderly shutdown begins (the encoder is kept to watch the axes).
  void begin(link::TimePoint now);
  [[nodiscard]] bool begun() const noexcept { return context_.begun_at.has_value(); }
  // Every cycle, before the sessions' transmit(). `stopping`: the monitor demands a stop of category
  // 0 or 1 — a device that moves something, lost meanwhile, is recovered and stopped at once, not only
  // once the run is over (under a category-2 hold nothing is recovered: the hold keeps the spindle
  // turning on purpose). From begin() on every device is brought to rest.
  void step(link::TimePoint now, bool stopping);
  // Every device present is resolved.
  [[nodiscard]] bool done() const noexcept;

  // Why a device's session gave up on it ("" if it never did).
  [[nodiscard]] std::string lost_reason(std::size_t slot) const;

  // After the loop: per device slot.
  [[nodiscard]] Verdicts verdicts() const;

 private:
  [[nodiscard]] const device_seam::CellDevice* at(std::size_t slot) const noexcept;

  CellDevices& devices_;
  device_seam::StopContext context_;
};

}  // namespace cellctl::runtime

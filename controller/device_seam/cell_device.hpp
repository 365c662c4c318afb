#pragma once
// One device of the cell as the controller sees it, above its session (as ros2_control's hardware
// interfaces are): its slot in the cell state and the intents, and its safe-stop policy — how it is
// stopped, what confirms its rest, its own bounds. The cycle (runtime::CellDevices) and the safe-stop
// (runtime::SafeStop) go through this interface only; what a device is stays in its own folder
// (devices/<name>/: codec, session, emulator) and in its adapter here (scu_device, spindle_device,
// encoder_device), which the registry (device_registry.hpp) makes.
//
// read() and apply() run in the cycle and allocate nothing; so do observe() and step_stop(). The
// evidence is composed after the loop.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "device_seam/device_safety.hpp"
#include "link/clock.hpp"
#include "link/device_session.hpp"

namespace cellctl::device_seam {

class CellDevice {
 public:
  // How often a lost device's port is opened and its session activated again.
  static constexpr link::Duration kRetry = std::chrono::milliseconds(100);
  // Opens the device's port again after it was lost (link::Link::reopen through the fault-injecting
  // and tracing links): true when the session may use its link again.
  using Reopen = std::function<bool()>;

  virtual ~CellDevice() = default;
  CellDevice(const CellDevice&) = delete;
  CellDevice& operator=(const CellDevice&) = delete;

  // Its place in the cell's arrays by device (CellState::links, the verdicts).
  [[nodiscard]] std::size_t slot() const noexcept { return slot_; }
  // How the config, the journal and the metrics name it ("scu").
  [[nodiscard]] std::string_view name() const noexcept { return name_; }
  // How sentences name it ("SCU").
  [[nodiscard]] std::string_view title() const noexcept { return title_; }
  [[nodiscard]] virtual link::DeviceSession& session() noexcept = 0;
  [[nodiscard]] virtual const link::DeviceSession& session() const noexcept = 0;

  // --- the cycle ---
  // Copies what its session knows into its slot of the cell state (after the session's receive()).
  virtual void read(link::TimePoint now, cell::CellState& out) = 0;
  // Hands what changed in its part of the intents to its session (before the session's transmit()).
  virtual void apply(const cell::Intents& intents) = 0;
  // What the session knows that the cell state cannot carry, in words, after the run (a fault reason,
  // a refused start).
  virtual void notes(std::vector<std::string>& out) const;

  // --- the safe-stop ---
  // Moves something of its own (actuators, a spindle): lost during the run under a stop of category 0
  // or 1, it is recovered and stopped at once. A device that only watches (the encoder) is not.
  [[nodiscard]] virtual bool moves() const noexcept { return true; }
  // Drives the cell's axes: a device that watches them is closed only once every such device is
  // resolved (StopContext::axes_resolved).
  [[nodiscard]] virtual bool drives_axes() const noexcept { return false; }
  // Every cycle of the run, after the cell state was read: what the device last said.
  virtual void observe(link::TimePoint now, const cell::CellState& state) noexcept;
  // The run is over: the orderly shutdown begins.
  virtual void begin_stop(link::TimePoint now) = 0;
  // Every cycle from begin_stop() on, and during the run once it was lost under a stop of category 0
  // or 1, until resolved.
  virtual void step_stop(link::TimePoint now, const StopContext& ctx) = 0;
  // Why the verdict is what it is, after the loop.
  [[nodiscard]] virtual std::string evidence(const StopContext& ctx) const = 0;

  [[nodiscard]] const std::optional<Safe>& resolved() const noexcept { return resolved_; }
  // Since its last good reply when its session gave up on it (nullopt: never lost), and why.
  [[nodiscard]] const std::optional<link::TimePoint>& lost_at() const noexcept { return lost_at_; }
  [[nodiscard]] const std::string& lost_reason() const noexcept { return lost_reason_; }

 protected:
  // `name` and `title` are static text.
  CellDevice(std::size_t slot, std::string_view name, std::string_view title, Reopen reopen);

  void note_loss(link::TimePoint now) noexcept;
  void resolve(Safe safe, link::TimePoint now) noexcept;
  // Opens the port again and activates the session, every kRetry.
  void recover(link::TimePoint now);
  // "SCU lost at 1.502 s (reason); port opened again 2 time(s), 1 attempt(s) refused; " — the part of
  // the evidence every device shares, `who` naming it.
  [[nodiscard]] std::string loss_evidence(std::string_view who, const StopContext& ctx) const;
  [[nodiscard]] link::TimePoint resolved_at() const noexcept { return resolved_at_; }

 private:
  std::size_t slot_;
  std::string_view name_;
  std::string_view title_;
  Reopen reopen_;
  std::optional<Safe> resolved_;
  link::TimePoint resolved_at_{};
  std::optional<link::TimePoint> lost_at_;
  std::string lost_reason_;  // the session's fault reason then (capacity reserved: no allocation)
  link::TimePoint next_retry_{};
  int reopen_failures_ = 0;
  int recoveries_ = 0;  // activations after a loss
};

}  // namespace cellctl::device_seam

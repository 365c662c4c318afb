#pragma once
// The SycoTec e@syDrive spindle converter as a device of the cell: read() fills the spindle's part of
// the cell state, apply() turns the spindle intent into start, stop, frequency change and reset.
//
// Its safe-stop: CMD System Stopp, sent again (port reopened, session activated again) until the
// converter reports STILLSTAND (observed). The converter has no communication watchdog (its manual
// names none): without an answer within `confirm_within` of the end it is unknown — it may still turn at
// the last set frequency. Never started since it was last seen at rest: bounded.

#include <optional>

#include "config/cell_config.hpp"
#include "device_seam/cell_device.hpp"
#include "spindle/session.hpp"

namespace cellctl::device_seam {

class SpindleDevice final : public CellDevice {
 public:
  // Throws std::invalid_argument (the session's config).
  SpindleDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link, Reopen reopen);

  [[nodiscard]] spindle::Session& spindle() noexcept { return session_; }
  [[nodiscard]] link::DeviceSession& session() noexcept override { return session_; }
  [[nodiscard]] const link::DeviceSession& session() const noexcept override { return session_; }

  void read(link::TimePoint now, cell::CellState& out) override;
  void apply(const cell::Intents& intents) override;
  void notes(std::vector<std::string>& out) const override;

  void observe(link::TimePoint now, const cell::CellState& state) noexcept override;
  void begin_stop(link::TimePoint now) override;
  void step_stop(link::TimePoint now, const StopContext& ctx) override;
  [[nodiscard]] std::string evidence(const StopContext& ctx) const override;

 private:
  struct StopWatch {
    double last_set_hz = 0.0;  // the last frequency a start or a change asked for
    bool run_sent = false;     // a start went out since the converter was last seen at rest
    std::optional<link::TimePoint> last_status;
    bool last_at_rest = true;
  };

  spindle::Session session_;
  StopWatch stop_;
};

}  // namespace cellctl::device_seam

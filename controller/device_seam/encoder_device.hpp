#pragma once
// The Scancon SCH88BEX encoder (through its DP master) as a device of the cell: read() fills the
// encoder's part of the cell state and the measured axes' positions, apply() runs the preset the
// intents ask for (its handshake) and reports how it ended.
//
// Its safe-stop: it moves nothing of its own; observed while its positions could be watched to the
// end, bounded (nothing to stop) when its link was lost. It is closed once whatever drives the axes is
// resolved: it watches them until then.

#include <cstdint>
#include <optional>
#include <string_view>

#include "config/cell_config.hpp"
#include "device_seam/cell_device.hpp"
#include "encoder/session.hpp"

namespace cellctl::device_seam {

class EncoderDevice final : public CellDevice {
 public:
  // Throws std::invalid_argument (the session's config).
  EncoderDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link, Reopen reopen);

  [[nodiscard]] encoder::Session& encoder() noexcept { return session_; }
  [[nodiscard]] link::DeviceSession& session() noexcept override { return session_; }
  [[nodiscard]] const link::DeviceSession& session() const noexcept override { return session_; }

  void read(link::TimePoint now, cell::CellState& out) override;
  void apply(const cell::Intents& intents) override;
  void notes(std::vector<std::string>& out) const override;

  [[nodiscard]] bool moves() const noexcept override { return false; }
  void observe(link::TimePoint now, const cell::CellState& state) noexcept override;
  void begin_stop(link::TimePoint) override {}  // kept to watch the axes until they are resolved
  void step_stop(link::TimePoint now, const StopContext& ctx) override;
  [[nodiscard]] std::string evidence(const StopContext& ctx) const override;

 private:
  struct Preset {
    std::uint32_t id = 0;  // the intent's preset_id last taken
    bool sent = false;
    bool done = false;
    bool failed = false;
    std::string_view failure;
  };
  struct StopWatch {
    std::optional<link::TimePoint> last_seen;  // in data exchange
    bool missed = false;  // out of data exchange in a cycle after the end: not watched to the end
    double mm = 0.0;
  };

  void follow_preset();

  const config::CellConfig& cell_;
  encoder::Session session_;
  Preset preset_;
  StopWatch stop_;
};

}  // namespace cellctl::device_seam

#pragma once
// The Ewellix SCU as a device of the cell. Its actuators are the cell's axes (each by the config's
// actuator and function numbers): read() fills the axes' SCU part of the cell state, apply() turns the
// axes' intents into moves, speed changes and stops (F20 under a category-0 halt).
//
// Its safe-stop: stopped and closed in order (RS, RA). A session that lost its SCU (port gone, silence,
// garbage) is given its port again and activated again every kRetry; once it is back, F20 stops every
// actuator and a refresh after the F20 shows whether they are at rest (observed). Attempts end at the
// first bound: the SCU's communication time-out (scu::kWatchdogPeriod after the last request that may
// have reached it, whatever the Safety_ID: every motion of ours is remote) plus the actuators' stopping
// time (scu.stopping_time_ms); rest is bounded once the last request sent is that long ago. The
// evidence names the last positions, the SCU's and, where the encoder measures an axis, the encoder's.

#include <array>
#include <cstdint>
#include <optional>

#include "config/cell_config.hpp"
#include "device_seam/cell_device.hpp"
#include "scu/session.hpp"

namespace cellctl::device_seam {

class ScuDevice final : public CellDevice {
 public:
  // Throws std::invalid_argument (the session's config).
  ScuDevice(std::size_t slot, const config::CellConfig& cell, link::Link& link, Reopen reopen);

  [[nodiscard]] scu::Session& scu() noexcept { return session_; }
  [[nodiscard]] bool drives_axes() const noexcept override { return true; }
  [[nodiscard]] link::DeviceSession& session() noexcept override { return session_; }
  [[nodiscard]] const link::DeviceSession& session() const noexcept override { return session_; }

  void read(link::TimePoint now, cell::CellState& out) override;
  void apply(const cell::Intents& intents) override;

  void observe(link::TimePoint now, const cell::CellState& state) noexcept override;
  void begin_stop(link::TimePoint now) override;
  void step_stop(link::TimePoint now, const StopContext& ctx) override;
  [[nodiscard]] std::string evidence(const StopContext& ctx) const override;

 private:
  struct AxisCommand {
    std::uint32_t applied_move = 0;   // the last move id the SCU accepted
    bool stop_sent = false;           // a stop went out for the motion now ending
    bool stop_soft = false;           // and it was a soft one
    std::uint64_t stop_refusals = 0;  // the SCU's refusal count when it went (a new refusal: send again)
    // The move the session refused for good (a cause that does not pass by itself: asked again, it
    // would be refused again) and why; not asked again until the next move, and read as refused.
    std::uint32_t refused_move = 0;
    scu::CommandStatus refusal = scu::CommandStatus::taken;
  };
  struct StopWatch {
    link::TimePoint bound_at{};              // communication time-out + stopping time after last_sent
    std::optional<link::TimePoint> give_up;  // no attempt after the first bound
    bool f20_asked = false;
    std::optional<std::uint64_t> refreshes_at_f20;
    std::optional<link::TimePoint> rest_seen_at;  // a refresh after the stop showed every actuator at rest
    std::optional<link::TimePoint> closed_at;     // RA answered
    bool moving_at_close = false;
    std::array<double, cell::kMaxAxes> last_mm{};
    std::optional<link::TimePoint> last_refresh;
    // The encoder's last reading in data exchange, for the axes it measures.
    std::optional<link::TimePoint> measured_at;
    double measured_mm = 0.0;
    double measured_mm_s = 0.0;
  };

  void halt_immediately(const scu::Snapshot& snap);
  void apply_axis(std::size_t i, const cell::Intents& in, const scu::Snapshot& snap);
  [[nodiscard]] bool all_at_rest() const noexcept;
  [[nodiscard]] const scu::ActuatorState& actuator_of(const scu::Snapshot& snap, std::size_t axis) const;

  const config::CellConfig& cell_;
  scu::Session session_;
  std::array<AxisCommand, cell::kMaxAxes> axis_cmd_{};
  bool estop_requested_ = false;      // an F20 went to the session for the halt in force
  std::uint64_t estop_refusals_ = 0;  // the SCU's refusal count then
  StopWatch stop_;
};

}  // namespace cellctl::device_seam

#pragma once
// The three device sessions seen as one cell: their snapshots become the CellState (in mm, mm/s, Hz;
// conversion to edges, counts and % happens here, from the config, and nowhere else), and changes
// of the supervisor's Intents become session commands. Non-blocking and allocation-free per cycle.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_config.hpp"
#include "encoder/session.hpp"
#include "link/link.hpp"
#include "runtime/device_links.hpp"
#include "scu/session.hpp"
#include "spindle/session.hpp"

namespace cellctl::runtime {

class CellDevices {
 public:
  // Throws std::invalid_argument (a session's config) — at construction only.
  CellDevices(const config::CellConfig& cell, DeviceLinks links);

  void activate(link::TimePoint now);
  // Orderly shutdown: axes stopped and remote mode closed (RA), spindle stopped.
  void deactivate(link::TimePoint now);
  void poll(link::TimePoint now);
  [[nodiscard]] bool all_inactive() const noexcept;

  // The snapshot of the cell now.
  void read(link::TimePoint now, cell::CellState& out);
  // Issues what changed in `intents` since the last call.
  void apply(const cell::Intents& intents, link::TimePoint now);

  [[nodiscard]] scu::Session* scu() noexcept { return scu_.get(); }
  [[nodiscard]] spindle::Session* spindle() noexcept { return spindle_.get(); }
  [[nodiscard]] encoder::Session* encoder() noexcept { return encoder_.get(); }

 private:
  struct AxisCommand {
    std::uint32_t applied_move = 0;   // the last move id the SCU accepted
    std::uint16_t speed_percent = 0;  // the last speed sent for it
    bool stop_sent = false;           // a stop went out for the motion now ending
    std::uint64_t stop_refusals = 0;  // the SCU's refusal count when it went (a new refusal: send again)
  };
  [[nodiscard]] std::uint16_t percent(std::size_t axis, double mm_s) const noexcept;
  void apply_axes(const cell::Intents& in);
  void apply_spindle(const cell::Intents& in);
  void poll_homed(link::TimePoint now);

  const config::CellConfig& cell_;
  std::unique_ptr<scu::Session> scu_;
  std::unique_ptr<spindle::Session> spindle_;
  std::unique_ptr<encoder::Session> encoder_;
  std::array<AxisCommand, cell::kMaxAxes> axis_cmd_{};
  bool estop_requested_ = false;      // an F20 went to the session for the halt in force
  std::uint64_t estop_refusals_ = 0;  // the SCU's refusal count then
  bool status2_known_ = false;
  bool spindle_running_ = false;
  double spindle_hz_ = 0.0;
  bool spindle_cw_ = true;
  std::optional<link::TimePoint> at_speed_since_;
  std::uint64_t encoder_diag_reads_ = 0;
  std::uint8_t homed_bits_ = 0;  // actuator status 2 bit 0 per actuator, from RG 0x00E0
  std::uint64_t homed_read_sequence_ = 0;
  link::TimePoint next_homed_read_{};
  link::TimePoint activated_at_{};
};

}  // namespace cellctl::runtime

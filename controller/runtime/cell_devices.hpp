#pragma once
// The three device sessions seen as one cell. It composes and decodes nothing itself: each session
// publishes its snapshot in program units with typed flags (mm, mm/s, Hz; the SCU's status bits, its
// "initialised" bits and error word, the encoder's counts are the sessions' business), and this class
// copies them into the CellState and turns changes of the supervisor's Intents into session commands.
// Each cycle: receive(now) → read(now, state) → … → apply(intents) → transmit(now), so a command
// decided in cycle k goes out in cycle k. Non-blocking and allocation-free per cycle.

#include <array>
#include <cstdint>
#include <memory>

#include "cell/cell_state.hpp"
#include "cell/intents.hpp"
#include "config/cell_config.hpp"
#include "encoder/session.hpp"
#include "link/device_session.hpp"
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
  void receive(link::TimePoint now);
  void transmit(link::TimePoint now);
  [[nodiscard]] bool all_inactive() const noexcept;

  // The snapshot of the cell now (after receive()).
  void read(link::TimePoint now, cell::CellState& out);
  // Hands what changed in `intents` to the sessions (before transmit()).
  void apply(const cell::Intents& intents);

  [[nodiscard]] scu::Session* scu() noexcept { return scu_.get(); }
  [[nodiscard]] spindle::Session* spindle() noexcept { return spindle_.get(); }
  [[nodiscard]] encoder::Session* encoder() noexcept { return encoder_.get(); }
  // The sessions there are, by cell::Device (nullptr for a device the cell lacks).
  [[nodiscard]] const std::array<link::DeviceSession*, cell::kDevices>& sessions() const noexcept {
    return sessions_;
  }

 private:
  struct AxisCommand {
    std::uint32_t applied_move = 0;   // the last move id the SCU accepted
    bool stop_sent = false;           // a stop went out for the motion now ending
    bool stop_soft = false;           // and it was a soft one
    std::uint64_t stop_refusals = 0;  // the SCU's refusal count when it went (a new refusal: send again)
  };
  void apply_axes(const cell::Intents& in);
  void apply_spindle(const cell::Intents& in);
  void apply_encoder(const cell::Intents& in);

  const config::CellConfig& cell_;
  std::unique_ptr<scu::Session> scu_;
  std::unique_ptr<spindle::Session> spindle_;
  std::unique_ptr<encoder::Session> encoder_;
  std::array<link::DeviceSession*, cell::kDevices> sessions_{};
  std::array<AxisCommand, cell::kMaxAxes> axis_cmd_{};
  struct Preset {
    std::uint32_t id = 0;  // the intent's preset_id last taken
    bool sent = false;
    bool done = false;
    bool failed = false;
    std::string_view failure;
  };
  Preset preset_;
  bool estop_requested_ = false;      // an F20 went to the session for the halt in force
  std::uint64_t estop_refusals_ = 0;  // the SCU's refusal count then
};

}  // namespace cellctl::runtime

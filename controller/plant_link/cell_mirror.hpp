#pragma once
// What the plant knows of the cell, kept on the link's thread from the run's events: the PackML state
// and mode, the step, the admin counters and the last stop reason, the latest sample. It renders the
// payloads of the state, mode, admin and status tags (packml_tags.hpp). Pure: no network, no clock.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/run_event.hpp"

namespace cellctl::plant_link {

// What a run event changed, so that only changed retained tags are published again.
struct Changed {
  bool state = false;
  bool mode = false;
  bool admin = false;
};

// The status the control cycle publishes (status::StatusBoard), as far as the plant reads it.
struct LiveStatus {
  bool known = false;
  double t = 0.0;
  std::uint32_t step = 0;
  std::uint32_t steps = 0;
  std::string label;
  double jitter_max_us = 0.0;
};

class CellMirror {
 public:
  // The cell's axes, in its order; `run_mode` is "hardware", "emulated", "virtual-time" or ""
  // when there is no run (cellctl emulate alone).
  CellMirror(const config::CellCore& cell, std::string run_mode);

  Changed apply(const RunEvent& e);

  [[nodiscard]] const std::string& state() const noexcept { return state_; }
  [[nodiscard]] nlohmann::json state_tag() const;
  [[nodiscard]] nlohmann::json mode_tag() const;
  [[nodiscard]] nlohmann::json admin_tag() const;
  // `link`: the link's own health (connected, reconnects, dropped) — added by the link.
  [[nodiscard]] nlohmann::json status_tag(const LiveStatus& live) const;

 private:
  std::vector<std::string> axes_;
  std::string run_mode_;
  std::string state_ = "Idle";
  double state_t_ = 0.0;
  std::string state_reason_;
  std::string recipe_;
  std::uint64_t runs_ = 0;
  std::uint64_t steps_done_ = 0;
  std::uint64_t steps_failed_ = 0;
  std::uint64_t faults_ = 0;
  std::uint64_t processed_ = 0;  // runs completed (PackML Admin.ProdProcessedCount)
  std::uint32_t step_ = 0;
  std::uint32_t steps_ = 0;
  std::string step_label_;
  nlohmann::json stop_reason_;  // null until something stopped the cell
  std::vector<nlohmann::json> active_faults_;
  RunEvent sample_;
  bool has_sample_ = false;
};

}  // namespace cellctl::plant_link

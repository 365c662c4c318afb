#pragma once
// What the plant knows of the cell, kept on the link's thread from the run's events: the PackML state
// and mode, the step, the admin counters and the last stop reason, the latest sample. It gives the
// state, mode, admin and status tags, typed (their payloads: schema/plant_tags.hpp). Pure: no network,
// no clock.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/run_event.hpp"
#include "schema/plant_tags.hpp"

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
  [[nodiscard]] schema::StateTag state_tag() const;
  [[nodiscard]] schema::ModeTag mode_tag() const;
  [[nodiscard]] const schema::AdminTag& admin_tag() const noexcept { return admin_; }
  // Without the link's own health: the link adds it.
  [[nodiscard]] schema::StatusTag status_tag(const LiveStatus& live) const;

 private:
  struct Axis {
    std::string name;
    int decimals = 3;  // of its positions: its SCU's resolution (tag_resolution.hpp)
  };
  std::vector<Axis> axes_;
  std::string run_mode_;
  std::string state_ = "Idle";
  double state_t_ = 0.0;
  std::string state_reason_;
  std::string recipe_;
  bool producing_ = false;  // a recipe's run is in progress: its end counts as processed or defective
  schema::AdminTag admin_;
  std::uint32_t step_ = 0;
  std::uint32_t steps_ = 0;
  std::string step_label_;
  RunEvent sample_;
  bool has_sample_ = false;
};

}  // namespace cellctl::plant_link

#pragma once
// The home record: what homing found per axis (strategy, encoder and SCU positions at home, when),
// and the config it was found with. Homed is a fact the next process checks against the devices
// before any motion (check_homed): the SCU still initialised (a power loss or reset clears it), the
// encoder and the SCU still in the relation they had at home (a replaced, re-preset or slipped
// encoder breaks it), the config unchanged. Plain data, no I/O: runtime/home_record_file.hpp reads and writes
// it.

#include <array>
#include <cstdint>
#include <string>

#include "cell/cell_state.hpp"
#include "config/cell_core.hpp"
#include "journal/event.hpp"

namespace cellctl::routines {

struct AxisHome {
  bool homed = false;
  config::HomingStrategy strategy = config::HomingStrategy::none;
  bool measured = false;  // the encoder measures the axis: encoder_mm is meaningful
  double encoder_mm = 0.0;
  double scu_mm = 0.0;
  double run_t = 0.0;          // homed in this run at this time (s since its start), else
  std::int64_t unix_time = 0;  // when it was homed (seconds since the epoch, UTC)
};

struct HomeRecord {
  std::string config_sha256;    // of the cell's config file now (what a record written now holds)
  bool config_changed = false;  // set by the loader: the record on disk was made with another config
  std::array<AxisHome, cell::kMaxAxes> axes{};  // by cell axis index
  bool updated = false;                         // homing in this run changed it: to be written
};

// Why axis `axis` is not homed now, or an empty text when the record holds against the devices.
[[nodiscard]] journal::Text check_homed(const HomeRecord& record, const config::CellCore& cell,
                                        const cell::CellState& s, std::size_t axis);

// The relation between encoder and SCU that the record is checked on: where the encoder should read
// when the SCU reads `scu_mm`.
[[nodiscard]] double expected_encoder_mm(const AxisHome& home, double scu_mm) noexcept;

}  // namespace cellctl::routines

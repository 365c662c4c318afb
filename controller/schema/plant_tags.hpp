#pragma once
// The cell's PackML tags as the plant reads them on its broker (plant_link/packml_tags.hpp lists the
// topics) and the operator page shows them in its live events: the payloads, typed, and their JSON.
// plant_link::CellMirror keeps what they say from the run's events; the link and the page publish them.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cellctl::schema {

// state: {"StateCurrent":6,"state":"Execute","t":…,"reason":…}
struct StateTag {
  int state_current = 0;  // PackML's number
  std::string state;
  double t = 0.0;
  std::string reason;  // none when empty
};

// mode: {"UnitModeCurrent":2,"mode":"dry-run virtual time","recipe":…}
struct ModeTag {
  int unit_mode_current = 0;
  std::string mode;
  std::string recipe;
};

// What stopped (or held) the cell last: a stopping state's reason, a failed step, an operator's
// command or a fault, each with the words a dashboard shows.
struct StopReason {
  enum class By { state, step, command, fault } by = By::state;
  double t = 0.0;
  std::string text;
  std::string state;            // by state
  std::uint32_t step = 0;       // by step
  std::string command, source;  // by command
  std::string fault;            // by fault, with its stop category
  std::uint8_t category = 0;
};

struct ActiveFault {
  std::string rule;
  std::uint8_t category = 0;
  std::string text;
  double t = 0.0;
  std::optional<std::string> remedy;  // the operator page's advice (web/fault_remedy.hpp)
};

// admin: the counters of PackML's Admin.* and the last stop's reason.
struct AdminTag {
  std::uint64_t runs = 0;
  std::uint64_t steps_done = 0;
  std::uint64_t steps_failed = 0;
  std::uint64_t faults = 0;
  std::uint64_t processed = 0;            // Admin.ProdProcessedCount: recipe runs completed
  std::uint64_t defective = 0;            // Admin.ProdDefectiveCount: recipe runs ended Stopped or Aborted
  std::optional<StopReason> stop_reason;  // null until something stopped the cell
  std::vector<ActiveFault> active_faults;
};

// status: where the run is, the axes, the spindle, the loop; the link adds its own health. Its numbers
// are given to their devices' resolution (plant_link/tag_resolution.hpp), as the payload writes them.
struct StatusTag {
  double t = 0.0;
  std::string state;
  std::uint32_t step = 0;
  std::uint32_t steps = 0;
  std::string label;
  double progress = 0.0;
  struct Axis {
    std::string name;
    std::optional<double> planned_mm;  // from the latest sample, when there is one for the axis
    std::optional<double> measured_mm;
  };
  std::vector<Axis> axes;
  struct Sampled {  // the latest sample's, when there is one
    double encoder_mm = 0.0;
    double spindle_set_hz = 0.0;
    double spindle_hz = 0.0;  // also PackML Status.CurMachSpeed: this cell's machine speed
  };
  std::optional<Sampled> sampled;
  double jitter_max_us = 0.0;
  struct Link {  // the plant link's own health
    std::uint64_t reconnects = 0;
    std::uint64_t dropped_status = 0;
    std::uint64_t dropped_events = 0;
    std::uint64_t ignored_retained = 0;
    std::string mqtt;  // the protocol spoken: "5", "3.1.1"
  };
  std::optional<Link> link;
};

[[nodiscard]] std::string state_payload(const StateTag& tag);
[[nodiscard]] std::string mode_payload(const ModeTag& tag);
[[nodiscard]] std::string admin_payload(const AdminTag& tag);
[[nodiscard]] std::string status_payload(const StatusTag& tag);

// online: {"online":true,"client_id":…,"cell":…} at connect; {"online":false,"client_id":…,"reason":…}
// when cellctl ends, and as the broker's last will.
[[nodiscard]] std::string online_payload(const std::string& client_id, const std::string& cell);
[[nodiscard]] std::string offline_payload(const std::string& client_id, const std::string& reason);

// The operator page's first live event: {"cell":…}.
[[nodiscard]] std::string cell_payload(const std::string& cell);

}  // namespace cellctl::schema

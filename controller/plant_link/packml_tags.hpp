#pragma once
// The cell's PackML tags as the plant reads them (after the PackML companion specification, OPC 30050:
// StateCurrent, UnitModeCurrent, Status.*, Admin.*), and the command words it may send. Pure, no
// network; the payloads' JSON is the schema's (schema/plant_tags.hpp).
//
// Topics under <prefix>/<cell>/:
//   online   retained, QoS 1: {"online":true,…} at connect (birth); {"online":false,…} as the broker's
//            last will (the controller died or lost the network) or when cellctl ends
//   state    retained, QoS 1, on every change: {"StateCurrent":6,"state":"Execute","t":…}
//   mode     retained, QoS 1, on every change: {"UnitModeCurrent":1,"mode":"production",…}
//   status   QoS 0, every status_ms: step, axes planned/measured, spindle set/actual, loop jitter, link
//   admin    retained, QoS 1, on every change: runs, steps, faults, ProdProcessedCount, StopReason
//   cmd/<hold|unhold|stop|abort|reset|start>   commands (payload: optional JSON {"id":…,"recipe":…})
//   response QoS 1: {"command":…,"id":…,"ok":true|false,"outcome"|"reason":…} for every command

#include <optional>
#include <string_view>

#include "supervisor/packml.hpp"

namespace cellctl::plant_link {

// PackML's state numbers (ISA-TR88.00.02 / OPC 30050 StateCurrent).
[[nodiscard]] int packml_state_number(std::string_view state_name) noexcept;

// The run's mode as PackML's UnitModeCurrent: production on hardware (1), dry runs on emulators are
// maintenance (2) — nothing real moves; no run at all (cellctl emulate alone) is reported as 0 (none).
struct UnitMode {
  int number = 0;
  std::string_view name;  // "production", "dry-run emulated", "dry-run virtual time", "none"
};
[[nodiscard]] UnitMode unit_mode(
    std::string_view run_mode) noexcept;  // "hardware", "emulated", "virtual-time"

}  // namespace cellctl::plant_link

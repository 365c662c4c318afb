#pragma once
// The page's "board" live event, made from the run's status board (status/status_view.hpp): per axis
// its target, the SCU's and the encoder's positions, each named as such, and whether it is homed (the
// home record's entry and the SCU's initialised bit, apart); per device — every slot the cell state
// carries a device in, by its name — its link's health (up, round trip, errors, last good reply). A
// view from a job that has ended is shown as such (live false). Pure: no clock, no I/O.
//
// {"live":true,"t":…,"axes":[{"name":"x","target_mm":40.0|null,"scu_mm":…|null,"encoder_mm":…|null,
//   "homed":{"record":true,"scu":true}}],
//  "devices":[{"name":"scu","link":"up"|"lost"|"down","round_trip_ms":…,"last_good_s":…,"replies":…,
//   "timeouts":…,"bad_frames":…,"refusals":…,"safe":"observed"|"bounded"|"unknown" (once the run's stop
//   resolved it)}],"spindle":{"set_hz":…,"actual_hz":…}}
// (without a view: {"live":false,"axes":[{"name":"x"}…],"devices":[]}).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "status/status_view.hpp"

namespace cellctl::web {

// `axis_names`: the cell's axes in their order (config::CellCore::axes).
[[nodiscard]] nlohmann::json board_payload(const std::vector<std::string>& axis_names,
                                           const std::optional<status::StatusView>& view, bool live);

}  // namespace cellctl::web

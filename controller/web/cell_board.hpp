#pragma once
// The page's "board" live event, made from the run's status board (status/status_view.hpp): per axis
// its target, the SCU's and the encoder's positions, each named as such, and whether it is homed (the
// home record's entry and the SCU's initialised bit, apart); per device — every slot the cell state
// carries a device in, by its name — its link's health (up, round trip, errors, last good reply) and
// its safe state once the run's stop resolved it. A view from a job that has ended is shown as such
// (live false). The operator page adds the state, the buttons and whether it lists run records; the
// JSON is the schema's (schema/page_payloads.hpp). Pure: no clock, no I/O.

#include <optional>
#include <string>
#include <vector>

#include "schema/page_payloads.hpp"
#include "status/status_view.hpp"

namespace cellctl::web {

// `axis_names`: the cell's axes in their order (config::CellCore::axes).
[[nodiscard]] schema::Board board_view(const std::vector<std::string>& axis_names,
                                       const std::optional<status::StatusView>& view, bool live);

}  // namespace cellctl::web

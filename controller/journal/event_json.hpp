#pragma once
// One journal line per event: {"t": 1.234, "event": "step_started", …}.

#include <nlohmann/json.hpp>

#include "journal/event.hpp"

namespace cellctl::journal {

[[nodiscard]] nlohmann::json to_json(const Event& e);

}  // namespace cellctl::journal

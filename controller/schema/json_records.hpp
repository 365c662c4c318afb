#pragma once
// The schema's own: the records of a line read back, from its JSON (read_journal_line.cpp).

#include <nlohmann/json.hpp>
#include <optional>

#include "schema/record_header.hpp"
#include "schema/summary_line.hpp"

namespace cellctl::schema {

[[nodiscard]] RecordHeader header_of(const nlohmann::json& line);
[[nodiscard]] std::optional<LoopFigures> loop_figures_of(const nlohmann::json& summary);

}  // namespace cellctl::schema

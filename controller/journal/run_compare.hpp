#pragma once
// `cellctl compare RUN_A RUN_B`: two runs of one recipe (a dry run and a real one, or two real
// ones) step by step — duration, where each axis ended against its plan, the spindle at each step's
// end — and overlaid in one plot (plot_svg.hpp / plot_html.hpp with both records).

#include <optional>
#include <string>

#include "journal/run_record.hpp"

namespace cellctl::journal {

// Why the two records are not runs of the same recipe (its file's SHA-256 differs, or its name when
// a record has no hash), or nullopt when they are.
[[nodiscard]] std::optional<std::string> different_recipes(const RunRecord& a, const RunRecord& b);

[[nodiscard]] std::string compare_text(const RunRecord& a, const RunRecord& b);

}  // namespace cellctl::journal

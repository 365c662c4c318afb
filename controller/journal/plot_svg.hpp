#pragma once
// A plot a person can open in any browser: axis positions (planned, SCU, encoder) and the spindle
// frequency against time, from the run's samples.

#include <string>
#include <utility>
#include <vector>

#include "journal/event.hpp"
#include "journal/run_summary.hpp"

namespace cellctl::journal {

[[nodiscard]] std::string render_svg(const std::vector<std::pair<double, Sample>>& samples,
                                     const RunSummary& summary);

}  // namespace cellctl::journal

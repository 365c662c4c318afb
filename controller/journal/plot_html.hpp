#pragma once
// plot.html: the same panels, steps and marks as plot.svg (one PlotModel), in a single file that
// needs nothing but a browser — no network reference, the data and the script inside — with zoom
// (wheel, or drag a span; double-click to reset), pan (shift-drag), series switched on and off, and
// every series' value, the step and the marks under the cursor.

#include <string>
#include <vector>

#include "journal/run_record.hpp"

namespace cellctl::journal {

[[nodiscard]] std::string render_html(const std::vector<const RunRecord*>& runs);

}  // namespace cellctl::journal

#pragma once
// plot.svg: the run (or two runs overlaid) as a static picture any browser or viewer opens —
// positions, following error and spindle against time on round-numbered scales, step boundaries
// named, faults, injected faults and operator commands marked and listed.

#include <string>
#include <vector>

#include "journal/run_record.hpp"

namespace cellctl::journal {

[[nodiscard]] std::string render_svg(const std::vector<const RunRecord*>& runs);

}  // namespace cellctl::journal

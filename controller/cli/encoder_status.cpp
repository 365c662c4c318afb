#include "cli/encoder_status.hpp"

#include <fmt/format.h>

namespace cellctl::cli {

bool encoder_inputs_valid(const encoder::Snapshot& s) noexcept {
  return s.data_exchange && s.input_valid;
}

std::string encoder_input_lines(link::Lifecycle lifecycle, const encoder::Snapshot& s) {
  const double age_ms = link::to_seconds(s.input_age) * 1e3;
  // The age is of the last valid input; with none, it is the time since the bus was started.
  const auto last = s.had_valid_input
                        ? fmt::format("last valid input {:.1f} ms ago", age_ms)
                        : fmt::format("no valid input in the {:.1f} ms since the start", age_ms);
  const auto invalid = s.bad_inputs == 0 ? std::string() : fmt::format(", {} inputs INVALID", s.bad_inputs);
  auto out = fmt::format("bus            {} ({}), {} exchanges{}, {}\n", link::to_string(lifecycle),
                         profibus::to_string(s.dp_state), s.exchanges, invalid, last);
  if (s.input_valid)
    out += fmt::format("position       {} counts = {:.3f} mm\n", s.position_counts, s.position_mm);
  else if (s.data_exchange)
    out += fmt::format("position       INVALID: {} (no position taken from it)\n",
                       s.input_fault.empty() ? "not a position" : s.input_fault);
  else
    out += "position       none: not in data exchange\n";
  return out;
}

}  // namespace cellctl::cli

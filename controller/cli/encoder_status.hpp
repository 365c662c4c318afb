#pragma once
// What `cellctl encoder status` (and `diag`) says of the bus and the encoder's input, kept true: an
// input the session marked invalid (a Class 2 word with bit 31 set, Ready cleared by an alarm, …) is
// reported as invalid with its reason, never as a position, and "last input" is the last valid one.
// Pure text from a snapshot, so it is tested against a session without a terminal.

#include <string>

#include "encoder/session.hpp"
#include "link/lifecycle.hpp"

namespace cellctl::cli {

// The "bus" and "position" lines, each ending in a newline.
[[nodiscard]] std::string encoder_input_lines(link::Lifecycle lifecycle, const encoder::Snapshot& s);

// The encoder delivers positions: in data exchange and its last input valid. Status exits 1 otherwise.
[[nodiscard]] bool encoder_inputs_valid(const encoder::Snapshot& s) noexcept;

}  // namespace cellctl::cli

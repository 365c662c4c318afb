#pragma once
// The line limit of PROFIBUS DP-V0 Data_Exchange, the reference both DP benchmarks (the generic
// master/slave pair and the encoder) divide by — one formula, so the two ratios compare:
//
//   one cycle = TSYN (33 bit idle before the request) + request frame + min_TSDR (idle before the
//             reply) + reply frame, at the line's bits per character (11 for 8E1)
//
// Frame lengths come from the codec itself (SD2, or SD3 for exactly 8 data octets), so the reference
// follows the encoding rules.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "link/line_format.hpp"
#include "profibus/bus_timing.hpp"
#include "profibus/fdl_frame.hpp"

namespace cellctl::bench {

// Characters on the wire of a Data_Exchange frame carrying `data` octets (0 for a bare SD1).
[[nodiscard]] inline std::size_t dx_frame_chars(std::size_t data) {
  const std::array<std::uint8_t, profibus::kMaxData> zeros{};
  return profibus::encoded_size(
      profibus::make_frame(5, 2, 0x7d, std::span<const std::uint8_t>(zeros.data(), data)));
}

// Seconds one Data_Exchange cycle occupies the line at best: 1 / this is the line limit.
[[nodiscard]] inline double dx_cycle_wire_s(const link::LineFormat& line, std::uint32_t min_tsdr_bits,
                                            std::size_t outputs, std::size_t inputs) {
  const auto idle = profibus::bit_times(line, profibus::kTsynBits) + profibus::bit_times(line, min_tsdr_bits);
  const auto chars = dx_frame_chars(outputs) + dx_frame_chars(inputs);
  return link::to_seconds(idle) + static_cast<double>(chars * line.bits_per_char()) / line.baud;
}

}  // namespace cellctl::bench

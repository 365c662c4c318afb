#pragma once
// PROFIBUS counts its times in bit times (TSL, min_TSDR, TSYN); sessions and emulators schedule in
// Duration on the injected clock. One conversion, from the line's baud rate.

#include <cstdint>

#include "link/clock.hpp"
#include "link/line_format.hpp"

namespace cellctl::profibus {

// Idle time the sender keeps before every request (synchronisation time, 33 bits).
inline constexpr std::uint32_t kTsynBits = 33;

[[nodiscard]] inline link::Duration bit_times(const link::LineFormat& line, std::uint64_t bits) noexcept {
  return link::Duration{static_cast<link::Duration::rep>(bits * 1'000'000'000ull / line.baud)};
}

}  // namespace cellctl::profibus

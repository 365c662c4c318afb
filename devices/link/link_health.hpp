#pragma once
// How a device link is doing, kept by every session the same way: round-trip times, errors,
// retries and the time of the last good telegram, from which "silent past its deadline" follows.

#include <cstdint>
#include <optional>

#include "link/clock.hpp"

namespace cellctl::link {

struct LinkHealth {
  std::uint64_t good_replies = 0;
  std::uint64_t timeouts = 0;       // requests that got no (complete) answer in time
  std::uint64_t bad_frames = 0;     // CRC/checksum/length errors and garbage
  std::uint64_t retries = 0;        // requests sent again
  std::uint64_t error_replies = 0;  // well-formed replies that say the device refused
  Duration last_round_trip{};
  Duration max_round_trip{};
  // The longest time between two good replies: what a silence limit (the DP master's
  // lost_slave_time, the monitor's link_silence_ms) is judged against, seen from below it.
  Duration max_silence{};
  std::optional<TimePoint> last_good;  // when the last well-formed reply arrived

  void record_reply(TimePoint sent, TimePoint received) noexcept;
  // Time since the last good reply, or since `since` (e.g. session activation) when there was none.
  [[nodiscard]] Duration silent_for(TimePoint now, TimePoint since) const noexcept;
};

}  // namespace cellctl::link

#include "link/link_health.hpp"

#include <algorithm>

namespace cellctl::link {

void LinkHealth::record_reply(TimePoint sent, TimePoint received) noexcept {
  ++good_replies;
  last_round_trip = received - sent;
  max_round_trip = std::max(max_round_trip, last_round_trip);
  if (last_good) max_silence = std::max(max_silence, received - *last_good);
  last_good = received;
}

Duration LinkHealth::silent_for(TimePoint now, TimePoint since) const noexcept {
  const TimePoint ref = last_good ? std::max(*last_good, since) : since;
  return now > ref ? now - ref : Duration{0};
}

}  // namespace cellctl::link

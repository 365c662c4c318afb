#pragma once
// Steps any parties on one SimLink in virtual time, from event to event (the next octet on the wire,
// the next deadline of a party, at most 1 ms ahead). A party has next_deadline() and is stepped by
// poll(now) (encoder::Emulator, profibus::DpMaster, profibus::DpSlave) or, as a device session
// (encoder::Session), by receive(now) and transmit(now).

#include <algorithm>
#include <chrono>
#include <optional>
#include <type_traits>

#include "link/clock.hpp"
#include "link/device_session.hpp"
#include "link/sim_link.hpp"

namespace cellctl::encoder::testing {

template <class Party>
void step_party(Party& party, link::TimePoint now) {
  if constexpr (std::is_base_of_v<link::DeviceSession, Party>) {
    party.receive(now);
    party.transmit(now);
  } else {
    (void)party.poll(now);
  }
}

template <class Done, class... Parties>
bool run_line_until(link::VirtualClock& clock, const link::SimLink& sim, Done done, link::Duration limit,
                    Parties&... parties) {
  using namespace std::chrono_literals;
  const auto deadline = clock.now() + limit;
  while (clock.now() < deadline) {
    const auto now = clock.now();
    (step_party(parties, now), ...);
    if (done()) return true;
    auto next = now + 1ms;
    const auto consider = [&](std::optional<link::TimePoint> d) {
      if (d) next = std::min(next, std::max(*d, now + 1us));
    };
    consider(sim.next_delivery());
    (consider(parties.next_deadline()), ...);
    clock.advance_to(next);
  }
  return done();
}

}  // namespace cellctl::encoder::testing

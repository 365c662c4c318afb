#pragma once
// What can go wrong on the line between a session and its device, put there on purpose to rehearse
// it (cellctl run --fault) and to test the sessions' reactions: the kinds a FaultInjectingLink makes.

#include <cstdint>
#include <string_view>

#include "link/clock.hpp"

namespace cellctl::link {

enum class LinkFaultKind : std::uint8_t {
  silent,      // nothing passes either way; the port itself looks fine
  disconnect,  // the port reports itself gone, as a tty does when its cable or adapter is pulled
  corrupt,     // bits flipped on the line, so checksums fail
  garbage,     // random bytes mixed into the traffic
  delay,       // the device's replies arrive `delay` later
};

[[nodiscard]] constexpr std::string_view to_string(LinkFaultKind k) noexcept {
  switch (k) {
    case LinkFaultKind::silent:
      return "silent";
    case LinkFaultKind::disconnect:
      return "disconnect";
    case LinkFaultKind::corrupt:
      return "corrupt";
    case LinkFaultKind::garbage:
      return "garbage";
    case LinkFaultKind::delay:
      return "delay";
  }
  return "?";
}

struct LinkFault {
  LinkFaultKind kind = LinkFaultKind::silent;
  Duration delay{};  // for LinkFaultKind::delay
};

}  // namespace cellctl::link

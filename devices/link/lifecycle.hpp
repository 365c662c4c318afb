#pragma once
// The one lifecycle every device session follows (configure at construction → activate → deactivate),
// owned by the session's own state machine; a fault always comes with a reason.

#include <cstdint>
#include <string_view>

namespace cellctl::link {

enum class [[nodiscard]] Lifecycle : std::uint8_t{
    inactive,      // constructed and configured, nothing sent
    activating,    // opening the device (remote mode, start parameters, DP start-up …)
    active,        // cyclic exchange running; commands accepted
    deactivating,  // orderly shutdown in progress (stop motion, leave remote mode …)
    fault,         // link lost or device refused; fault_reason() says why; activate() again to retry
};

[[nodiscard]] constexpr std::string_view to_string(Lifecycle s) noexcept {
  switch (s) {
    case Lifecycle::inactive:
      return "inactive";
    case Lifecycle::activating:
      return "activating";
    case Lifecycle::active:
      return "active";
    case Lifecycle::deactivating:
      return "deactivating";
    case Lifecycle::fault:
      return "fault";
  }
  return "?";
}

}  // namespace cellctl::link

#pragma once
// A command as it reached this process: who sent it, when it arrived and, when the sender said so,
// when it was issued. Only a command meant now is obeyed: one that waited longer than the maximum
// age anywhere — a web worker's queue, the link's queue, the arbiter — is answered "expired" and not
// obeyed, judged by the later of its arrival and its issue time (a sender's clock may be behind ours;
// an issue time in the future beyond the same bound is refused as well: a clock that far off makes
// the age unknowable).

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "command/command_source.hpp"

namespace cellctl::command {

using SteadyTime = std::chrono::steady_clock::time_point;
using UtcTime = std::chrono::system_clock::time_point;

inline constexpr std::chrono::milliseconds kDefaultMaxCommandAge{2000};

struct Order {
  CommandSource source;
  SteadyTime received{};             // when it reached this process (its headers, its MQTT message)
  std::optional<UtcTime> issued_at;  // as the sender stamped it, UTC
};

// Why `o` is too old to obey at (`now`, `utc_now`), or empty when it is fresh.
[[nodiscard]] std::string expired(const Order& o, SteadyTime now, UtcTime utc_now,
                                  std::chrono::milliseconds max_age);

// RFC 3339 in UTC: "2026-11-27T19:50:00Z", with an optional fraction ("…:00.125Z") or "+00:00".
[[nodiscard]] std::optional<UtcTime> parse_utc(std::string_view text);

}  // namespace cellctl::command

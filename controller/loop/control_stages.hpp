#pragma once
// The stages of cellctl's control cycle, in the order the data flows (architecture.md): the
// default stage list of the Loop, indexed by ControlStage.

#include <array>
#include <cstddef>
#include <string_view>

namespace cellctl::loop {

enum class ControlStage : std::size_t { read_sessions, state, monitor, supervisor, write_sessions };

inline constexpr std::array<std::string_view, 5> kControlStages{"read sessions", "state", "monitor",
                                                                "supervisor", "write sessions"};

[[nodiscard]] constexpr std::size_t index(ControlStage s) noexcept {
  return static_cast<std::size_t>(s);
}

}  // namespace cellctl::loop

#pragma once
// A session's fault reason is composed in the cycle, at the moment the fault happens, yet poll() must
// not allocate: the session reserves kFaultReasonCapacity in its reason string at construction and
// formats into it here (a longer reason is cut, never reallocated).

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <utility>

namespace cellctl::link {

// As journal::Text's capacity: a fault reason is quoted whole in the journal, the terminal and MQTT.
inline constexpr std::size_t kFaultReasonCapacity = 1024;

template <class... Args>
void assign_formatted(std::string& out, fmt::format_string<Args...> format, Args&&... args) {
  std::array<char, kFaultReasonCapacity> buffer{};
  const auto r = fmt::format_to_n(buffer.data(), buffer.size(), format, std::forward<Args>(args)...);
  out.assign(buffer.data(), std::min(r.size, buffer.size()));
}

}  // namespace cellctl::link

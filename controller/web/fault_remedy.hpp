#pragma once
// What an operator should do about each of the safety monitor's faults, by its rule name (the
// journal's `rule`), for the web page. Text only; the monitor decides, this explains.

#include <string_view>

namespace cellctl::web {

[[nodiscard]] std::string_view fault_remedy(std::string_view rule) noexcept;

}  // namespace cellctl::web

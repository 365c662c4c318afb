#pragma once
// What an operator should do about each of the safety monitor's faults, by its rule name (the
// journal's `rule`), for the web page: the remedy in the monitor's rule table (monitor/rule.hpp), a
// pointer to the run record for a name that is no rule. Text only; the monitor decides, this explains.

#include <string_view>

namespace cellctl::web {

[[nodiscard]] std::string_view fault_remedy(std::string_view rule) noexcept;

}  // namespace cellctl::web

#include "web/fault_remedy.hpp"

#include "monitor/rule.hpp"

namespace cellctl::web {

std::string_view fault_remedy(std::string_view rule) noexcept {
  if (const auto r = monitor::rule_named(rule)) return monitor::rule_info(*r).remedy;
  return "See the run record (journal.jsonl) for what happened.";
}

}  // namespace cellctl::web

#pragma once
// The safety monitor's rules in one table: each rule's name (in the journal, on the terminal, the
// page and the plant link), the class of stop it demands and what an operator should do about it.
// The enum, the count and the table are made from the one list below, so a rule cannot lack a name,
// a stop or a remedy: a row without one does not compile.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace cellctl::monitor {

// Which of the cell config's `stops:` entries gives a rule its stop category (IEC 60204-1); the
// emergency stop is category 0 whatever the config says.
enum class StopClass : std::uint8_t { fault, link, following_error, operator_stop, emergency };

// X(rule, stop class, remedy), one row per rule, in the enum's order.
#define CELLCTL_MONITOR_RULES(X)                                                                             \
  /* an axis outside the cell's travel limits */                                                             \
  X(position_limit, fault,                                                                                   \
    "An axis left the cell's travel: check the recipe's targets and the axis scaling (edges_per_mm) "        \
    "before a reset.")                                                                                       \
  /* encoder velocity above the cell's limit */                                                              \
  X(overspeed, fault,                                                                                        \
    "The encoder measured more than the cell allows: check the encoder coupling and the SCU's speed "        \
    "scaling.")                                                                                              \
  /* SCU position and encoder position differ by more than the tolerance */                                  \
  X(disagreement, fault,                                                                                     \
    "SCU and encoder positions differ: check the encoder's coupling (slip) and preset; re-home if in "       \
    "doubt.")                                                                                                \
  /* an axis off its planned position by more than its speed allows (LinuxCNC's FERROR) */                   \
  X(following_error, following_error,                                                                        \
    "An axis fell behind its plan: look for an obstruction, a load or a worn actuator; reset, then unhold "  \
    "or restart.")                                                                                           \
  /* the encoder left data exchange or dropped its Ready bit */                                              \
  X(encoder_not_ready, fault,                                                                                \
    "The encoder left data exchange: check the PROFIBUS cable, terminator and the encoder's supply.")        \
  /* the encoder's diagnosis reports an alarm */                                                             \
  X(encoder_alarm, fault, "The encoder reports an alarm in its diagnosis: `cellctl encoder diag` names it.") \
  /* the encoder's limit-switch status bit */                                                                \
  X(encoder_limit_switch, fault,                                                                             \
    "The encoder's limit-switch bit is set: move the axis back inside its range by hand mode.")              \
  /* the encoder signals new diagnosis (DH) during the run */                                                \
  X(encoder_diagnosis, fault, "The encoder signals new diagnosis: read it with `cellctl encoder diag`.")     \
  /* the converter reports a fault */                                                                        \
  X(spindle_fault, fault,                                                                                    \
    "The converter reports a fault: `cellctl spindle status` names it; remove the cause, then reset.")       \
  /* motor PTC over-temperature */                                                                           \
  X(spindle_temperature, fault,                                                                              \
    "Motor over-temperature: let the spindle cool down and check its cooling before a reset.")               \
  /* actual frequency outside the allowed range, or off the set-point at speed */                            \
  X(spindle_frequency, fault,                                                                                \
    "The spindle is off its set frequency: check the load, the tool and the converter's limits.")            \
  /* a bit in the SCU's error word */                                                                        \
  X(scu_error, fault,                                                                                        \
    "The SCU reports an actuator error: `cellctl scu status` names the bit; check the actuator and its "     \
    "cable.")                                                                                                \
  /* a device link silent past its deadline */                                                               \
  X(link_silent, link,                                                                                       \
    "A device stopped answering: check its cable, adapter and power; the run cannot go on without it.")      \
  /* Ctrl-C or a stop command */                                                                             \
  X(operator_stop, operator_stop, "Stopped by an operator: reset, then unhold to go on, or stop to end.")    \
  /* an emergency stop command */                                                                            \
  X(emergency_stop, emergency, "Emergency stop: make the cell safe, find the cause, then reset.")

#define CELLCTL_RULE_ENUMERATOR(rule, stop, remedy) rule,
enum class Rule : std::uint8_t { CELLCTL_MONITOR_RULES(CELLCTL_RULE_ENUMERATOR) };
#undef CELLCTL_RULE_ENUMERATOR

struct RuleInfo {
  Rule rule;
  std::string_view name;
  StopClass stop;
  std::string_view remedy;  // for the operator (the web page)
};

#define CELLCTL_RULE_ROW(rule_, stop_, remedy_) \
  RuleInfo{.rule = Rule::rule_, .name = #rule_, .stop = StopClass::stop_, .remedy = remedy_},
inline constexpr std::array kRules = {CELLCTL_MONITOR_RULES(CELLCTL_RULE_ROW)};
#undef CELLCTL_RULE_ROW
#undef CELLCTL_MONITOR_RULES

inline constexpr std::size_t kRuleCount = kRules.size();

static_assert(
    [] {
      for (std::size_t i = 0; i < kRuleCount; ++i) {
        if (kRules[i].rule != static_cast<Rule>(i) || kRules[i].remedy.empty()) return false;
        for (std::size_t j = 0; j < i; ++j)
          if (kRules[j].name == kRules[i].name) return false;
      }
      return true;
    }(),
    "every rule in its place, with a remedy and a name of its own");

[[nodiscard]] constexpr const RuleInfo& rule_info(Rule r) noexcept {
  return kRules[static_cast<std::size_t>(r)];
}
[[nodiscard]] constexpr std::string_view to_string(Rule r) noexcept {
  return rule_info(r).name;
}

// The rule of that name (the journal's `rule`), if there is one.
[[nodiscard]] constexpr std::optional<Rule> rule_named(std::string_view name) noexcept {
  for (const auto& r : kRules)
    if (r.name == name) return r.rule;
  return std::nullopt;
}

}  // namespace cellctl::monitor

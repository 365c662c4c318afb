#include "web/fault_remedy.hpp"

#include <array>
#include <utility>

namespace cellctl::web {

std::string_view fault_remedy(std::string_view rule) noexcept {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 15> kRemedies{{
      {"position_limit",
       "An axis left the cell's travel: check the recipe's targets and the axis scaling (edges_per_mm) "
       "before a reset."},
      {"overspeed",
       "The encoder measured more than the cell allows: check the encoder coupling and the SCU's speed "
       "scaling."},
      {"disagreement",
       "SCU and encoder positions differ: check the encoder's coupling (slip) and preset; re-home if in "
       "doubt."},
      {"following_error",
       "An axis fell behind its plan: look for an obstruction, a load or a worn actuator; reset, then unhold "
       "or restart."},
      {"encoder_not_ready",
       "The encoder left data exchange: check the PROFIBUS cable, terminator and the encoder's supply."},
      {"encoder_alarm", "The encoder reports an alarm in its diagnosis: `cellctl encoder diag` names it."},
      {"encoder_limit_switch",
       "The encoder's limit-switch bit is set: move the axis back inside its range by hand mode."},
      {"encoder_diagnosis", "The encoder signals new diagnosis: read it with `cellctl encoder diag`."},
      {"spindle_fault",
       "The converter reports a fault: `cellctl spindle status` names it; remove the cause, then reset."},
      {"spindle_temperature",
       "Motor over-temperature: let the spindle cool down and check its cooling before a reset."},
      {"spindle_frequency",
       "The spindle is off its set frequency: check the load, the tool and the converter's limits."},
      {"scu_error",
       "The SCU reports an actuator error: `cellctl scu status` names the bit; check the actuator and its "
       "cable."},
      {"link_silent",
       "A device stopped answering: check its cable, adapter and power; the run cannot go on without it."},
      {"operator_stop", "Stopped by an operator: reset, then unhold to go on, or stop to end."},
      {"emergency_stop", "Emergency stop: make the cell safe, find the cause, then reset."},
  }};
  for (const auto& [name, text] : kRemedies)
    if (name == rule) return text;
  return "See the run record (journal.jsonl) for what happened.";
}

}  // namespace cellctl::web

// The page's remedy for each fault, by the journal's rule name: the texts the page showed before the
// remedies moved into the monitor's rule table, word for word, and the pointer to the run record for
// a name that is no rule.
#include "web/fault_remedy.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "monitor/rule.hpp"

namespace cellctl::web {
namespace {

TEST(FaultRemedy, EveryRuleHasTheRemedyThePageShowed) {
  const std::vector<std::pair<std::string, std::string>> shown = {
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
  };
  ASSERT_EQ(shown.size(), monitor::kRuleCount);
  for (const auto& [rule, text] : shown) EXPECT_EQ(fault_remedy(rule), text) << rule;
}

TEST(FaultRemedy, ANameThatIsNoRulePointsToTheRunRecord) {
  EXPECT_EQ(fault_remedy("no_such_rule"), "See the run record (journal.jsonl) for what happened.");
  EXPECT_EQ(fault_remedy(""), "See the run record (journal.jsonl) for what happened.");
}

}  // namespace
}  // namespace cellctl::web

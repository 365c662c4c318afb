// The monitor's rule table (monitor/rule.hpp): every rule found by its name, each with the stop class
// it had before the table and a remedy. (A row without a name, class or remedy, or one out of the
// enum's order, does not compile: the table's static_assert.)
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "monitor/rule.hpp"

namespace cellctl::monitor {
namespace {

TEST(RuleTable, EveryRuleIsFoundByItsNameAndNoOtherNameIsARule) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    const auto rule = static_cast<Rule>(i);
    const auto found = rule_named(to_string(rule));
    ASSERT_TRUE(found.has_value()) << to_string(rule);
    EXPECT_EQ(*found, rule);
    EXPECT_FALSE(rule_info(rule).remedy.empty()) << to_string(rule);
    names.insert(std::string(to_string(rule)));
  }
  EXPECT_EQ(names.size(), kRuleCount);
  EXPECT_FALSE(rule_named("").has_value());
  EXPECT_FALSE(rule_named("position_limits").has_value());
  EXPECT_FALSE(rule_named("Overspeed").has_value());
}

TEST(RuleTable, TheJournalsNamesAreAsBefore) {
  EXPECT_EQ(kRuleCount, 15u);
  EXPECT_EQ(to_string(Rule::position_limit), "position_limit");
  EXPECT_EQ(to_string(Rule::following_error), "following_error");
  EXPECT_EQ(to_string(Rule::spindle_frequency), "spindle_frequency");
  EXPECT_EQ(to_string(Rule::link_silent), "link_silent");
  EXPECT_EQ(to_string(Rule::emergency_stop), "emergency_stop");
}

TEST(RuleTable, EachRuleStopsWithTheConfigEntryOfItsClass) {
  for (const auto& r : kRules) {
    switch (r.rule) {
      case Rule::emergency_stop:
        EXPECT_EQ(r.stop, StopClass::emergency);
        break;
      case Rule::operator_stop:
        EXPECT_EQ(r.stop, StopClass::operator_stop);
        break;
      case Rule::link_silent:
        EXPECT_EQ(r.stop, StopClass::link);
        break;
      case Rule::following_error:
        EXPECT_EQ(r.stop, StopClass::following_error);
        break;
      default:
        EXPECT_EQ(r.stop, StopClass::fault) << r.name;
    }
  }
}

}  // namespace
}  // namespace cellctl::monitor

#include "runtime/fault_spec.hpp"

#include <gtest/gtest.h>

namespace cellctl::runtime {
namespace {

using namespace std::chrono_literals;

FaultSpec good(std::string_view text) {
  auto r = parse_fault_spec(text);
  if (auto* e = std::get_if<FaultSpecError>(&r)) ADD_FAILURE() << text << ": " << e->reason;
  return std::get_if<FaultSpec>(&r) ? std::get<FaultSpec>(r) : FaultSpec{};
}

std::string reason(std::string_view text) {
  auto r = parse_fault_spec(text);
  if (auto* e = std::get_if<FaultSpecError>(&r)) return e->reason;
  ADD_FAILURE() << text << " was accepted";
  return {};
}

TEST(FaultSpec, ReadsEachDeviceAndKind) {
  const auto s = good("scu:silent@2+1.5");
  EXPECT_EQ(s.device, "scu");
  ASSERT_TRUE(s.line);
  EXPECT_EQ(s.line->kind, link::LinkFaultKind::silent);
  EXPECT_EQ(s.at, 2s);
  EXPECT_EQ(s.lasting, 1500ms);
  EXPECT_EQ(s.text, "scu:silent@2+1.5");
  EXPECT_EQ(s.kind_name(), "silent");

  EXPECT_EQ(good("spindle:disconnect@0").line->kind, link::LinkFaultKind::disconnect);
  EXPECT_EQ(good("spindle:disconnect@0").device, "spindle");
  EXPECT_FALSE(good("spindle:disconnect@0").lasting) << "without +D it lasts for ever";
  EXPECT_EQ(good("encoder:corrupt@1.25").line->kind, link::LinkFaultKind::corrupt);
  EXPECT_EQ(good("encoder:corrupt@1.25").at, 1250ms);
  EXPECT_EQ(good("encoder:garbage@3+0.1").line->kind, link::LinkFaultKind::garbage);

  const auto d = good("spindle:delay=300@4+2");
  EXPECT_EQ(d.line->kind, link::LinkFaultKind::delay);
  EXPECT_EQ(d.line->delay, 300ms);
  EXPECT_EQ(d.kind_name(), "delay");
  EXPECT_EQ(good("scu:delay=0.5@0").line->delay, 500us);

  const auto e = good("encoder:error@10+5");
  EXPECT_FALSE(e.line) << "error is the device's own, not the line's";
  EXPECT_EQ(e.kind_name(), "error");
  EXPECT_EQ(e.device, "encoder");
}

TEST(FaultSpec, SaysWhatIsWrongWithBadText) {
  EXPECT_EQ(reason("scu"), "expected DEVICE:KIND@T[+D], e.g. scu:silent@2+1.5 or spindle:delay=300@4");
  EXPECT_EQ(reason("scu:silent"), reason("scu"));
  EXPECT_EQ(reason("silent@2:scu"), reason("scu"));
  EXPECT_EQ(reason("plc:silent@1"), "unknown device 'plc' (scu, spindle, encoder)");
  EXPECT_EQ(reason("SCU:silent@1"), "unknown device 'SCU' (scu, spindle, encoder)");
  EXPECT_EQ(reason("scu:quiet@1"),
            "unknown kind 'quiet' (silent, disconnect, corrupt, garbage, delay=MS, error)");
  EXPECT_EQ(reason("scu:@1"), "unknown kind '' (silent, disconnect, corrupt, garbage, delay=MS, error)");
  EXPECT_EQ(reason("scu:delay@1"), "delay needs its time in milliseconds: delay=MS, e.g. delay=300");
  for (const auto* bad : {"scu:delay=0@1", "scu:delay=-5@1", "scu:delay=abc@1", "scu:delay=@1",
                          "scu:delay=60001@1", "scu:delay=1e3@1"})
    EXPECT_NE(reason(bad).find("MS must be a number of milliseconds above 0 and at most 60000"),
              std::string::npos)
        << bad;
  EXPECT_EQ(reason("scu:silent@"),
            "time '': T must be the seconds after the run starts, from 0 to 86400 (then +D for how long)");
  for (const auto* bad : {"scu:silent@-1", "scu:silent@x", "scu:silent@1s", "scu:silent@nan",
                          "scu:silent@inf", "scu:silent@86401", "scu:silent@1.2.3", "scu:silent@+1"})
    EXPECT_NE(reason(bad).find("T must be the seconds after the run starts"), std::string::npos) << bad;
  EXPECT_EQ(
      reason("scu:silent@1+0"),
      "duration '0': D must be seconds above 0 and at most 86400 (leave out +D for a fault that lasts)");
  for (const auto* bad : {"scu:silent@1+", "scu:silent@1+-2", "scu:silent@1+2+3", "scu:silent@1+1 "})
    EXPECT_NE(reason(bad).find("D must be seconds above 0"), std::string::npos) << bad;
}

}  // namespace
}  // namespace cellctl::runtime

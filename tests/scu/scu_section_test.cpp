// The `scu:` section of the cell config: a valid section, the shipped cell.yaml, and malformed inputs
// with their exact file:line:column messages.

#include "config/scu_section.hpp"

#include <gtest/gtest.h>

#include "config/cell_config.hpp"
#include "emulation/emulator_setup.hpp"
#include "support/expect_config_error.hpp"

namespace cellctl::config {
namespace {

using namespace std::chrono_literals;

ScuSection parse(const std::string& text) {
  return parse_scu_section(YamlNode::load_string(text, "cell.yaml").at("scu"));
}

void expect_error(const std::string& text, const std::string& message) {
  cellctl::testing::expect_config_error([&] { (void)parse(text); }, message);
}

TEST(ScuSection, ParsesAValidSection) {
  const auto s = parse(
      "scu:\n"
      "  port: /dev/ttyUSB0\n"
      "  safety_id: 1\n"
      "  keepalive_ms: 50\n"
      "  reply_timeout_ms: 80\n"
      "  retries: 3\n"
      "  link_fault_after_ms: 600\n"
      "  actuators:\n"
      "    - {index: 1, edges_per_mm: 10, stroke_mm: 300, max_speed_mm_s: 25}\n"
      "    - {index: 3, edges_per_mm: 20}\n"
      "  functions:\n"
      "    - {id: 1, actuators: [1]}\n"
      "    - {id: 4, actuators: [1, 3], synchronized: true}\n");
  EXPECT_EQ(s.port.port, "/dev/ttyUSB0");
  EXPECT_EQ(s.port.line.baud, 38400u);
  EXPECT_EQ(s.session.safety_id, 1);
  EXPECT_EQ(s.session.keepalive_period, 50ms);
  EXPECT_EQ(s.session.reply_timeout, 80ms);
  EXPECT_EQ(s.session.retries, 3);
  EXPECT_EQ(s.session.link_fault_after, 600ms);
  EXPECT_EQ(s.session.actuators.to_ulong(), 0b101u);
  EXPECT_TRUE(s.session.functions[3].synchronized);
  EXPECT_TRUE(s.session.functions[3].moves(3));
  EXPECT_FALSE(s.session.functions[1].defined);
  EXPECT_DOUBLE_EQ(s.session.specs[2].edges_per_mm, 20.0);
  EXPECT_DOUBLE_EQ(s.session.specs[0].stroke_mm, 300.0);
  EXPECT_DOUBLE_EQ(s.session.specs[0].full_speed_mm_s, 25.0);
  EXPECT_NO_THROW(scu::validate(s.session));
}

TEST(ScuSection, DefaultsToScp11) {
  const auto s = parse("scu:\n  actuators:\n    - {index: 2, edges_per_mm: 10}\n");
  EXPECT_EQ(s.port.port, "emulated");
  EXPECT_TRUE(s.session.functions[1].moves(2));
  EXPECT_FALSE(s.session.functions[0].defined);
  EXPECT_EQ(s.session.keepalive_period, 100ms);
}

TEST(ScuSection, TheShippedCellConfigLoads) {
  const auto cell = load_cell_config(CELLCTL_SOURCE_DIR "/config/cell.yaml");
  ASSERT_TRUE(cell.scu.has_value());
  EXPECT_EQ(cell.scu->session.actuators.to_ulong(), 0b11u);
  EXPECT_NO_THROW(scu::validate(cell.scu->session));
  const auto emulated = emulation::load_emulator_setup(cell);
  ASSERT_TRUE(emulated.scu.has_value());
  EXPECT_NO_THROW(scu::validate(*emulated.scu));
  // The emulated actuator is the session's (scaling, stroke, speed) with the physics added.
  EXPECT_TRUE(emulated.scu->actuators[1].present);
  EXPECT_DOUBLE_EQ(emulated.scu->actuators[0].edges_per_mm, cell.scu->session.specs[0].edges_per_mm);
  EXPECT_DOUBLE_EQ(emulated.scu->actuators[0].physics.scale_error, 0.002);
  EXPECT_DOUBLE_EQ(emulated.scu->actuators[1].physics.ramp_mm_s2, 30.0);
}

TEST(ScuSection, MalformedInputsNameFileLineColumn) {
  expect_error("scu:\n  keepalive_ms: 600\n  actuators: [{index: 1, edges_per_mm: 10}]\n",
               "cell.yaml:2:17: scu.keepalive_ms: 600 is out of range [0, 400]");
  expect_error("scu:\n  safety_id: 3\n  actuators: [{index: 1, edges_per_mm: 10}]\n",
               "cell.yaml:2:14: scu.safety_id: 3 is out of range [0, 2]");
  expect_error("scu:\n  actuators:\n    - {index: 1, edges_per_mm: 10}\n    - {index: 1, edges_per_mm: 10}\n",
               "cell.yaml:4:15: scu.actuators[1].index: actuator 1 is listed twice");
  expect_error(
      "scu:\n  actuators:\n    - {index: 1, edges_per_mm: 10}\n  functions:\n    - {id: 1, actuators: [2]}\n",
      "cell.yaml:5:27: scu.functions[0].actuators[0]: actuator 2 is not in scu.actuators");
  expect_error("scu:\n  actuators:\n    - {index: 7, edges_per_mm: 10}\n",
               "cell.yaml:3:15: scu.actuators[0].index: 7 is out of range [1, 6]");
  expect_error(
      "scu:\n  reply_timeout_ms: 500\n  link_fault_after_ms: 400\n  actuators: [{index: 1, edges_per_mm: "
      "10}]\n",
      "cell.yaml:3:24: scu.link_fault_after_ms: link_fault_after_ms must be longer than reply_timeout_ms");
}

TEST(ScuSection, RejectsUnknownKeysAndMissingActuators) {
  EXPECT_THROW(parse("scu:\n  keepalive: 100\n  actuators: [{index: 1, edges_per_mm: 10}]\n"), ConfigError);
  EXPECT_THROW(parse("scu:\n  port: emulated\n"), ConfigError);
  EXPECT_THROW(parse("scu:\n  actuators: [{index: 1}]\n"), ConfigError) << "edges_per_mm is required";
}

}  // namespace
}  // namespace cellctl::config

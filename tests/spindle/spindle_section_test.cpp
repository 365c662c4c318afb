// The `spindle:` config section: defaults, every key read, and malformed input rejected with the
// exact file:line:column message an integrator sees.

#include "config/spindle_section.hpp"

#include <gtest/gtest.h>

#include "emulation/emulator_setup.hpp"
#include "support/expect_config_error.hpp"

namespace cellctl::config {
namespace {

using namespace std::chrono_literals;

SpindleSection parse(const std::string& text) {
  return parse_spindle_section(YamlNode::load_string(text, "cell.yaml").at("spindle"));
}
// The section's `emulator:` block, read where emulators are built.
spindle::EmulatorConfig emulator_of(const std::string& text) {
  const auto section = YamlNode::load_string(text, "cell.yaml").at("spindle");
  (void)parse_spindle_section(section);
  return emulation::parse_spindle_emulator(section);
}

using cellctl::testing::expect_config_error;

TEST(SpindleSection, DefaultsAreTheConvertersLineAndTheSessionDefaults) {
  const auto s = parse("spindle: {}\n");
  EXPECT_TRUE(s.port.emulated());
  EXPECT_EQ(s.port.publish_as, "/tmp/cellctl-spindle");
  EXPECT_EQ(s.port.line.baud, 38400u);
  EXPECT_EQ(s.port.line.bits_per_char(), 10u);
  EXPECT_EQ(s.session.reply_timeout, spindle::SessionConfig{}.reply_timeout);
  EXPECT_EQ(emulator_of("spindle: {}\n").max_hz, spindle::EmulatorConfig{}.max_hz);
}

TEST(SpindleSection, ReadsEveryKey) {
  const std::string text =
      "spindle:\n"
      "  port: /dev/ttyUSB1\n"
      "  baud: 19200\n"
      "  reply_timeout_ms: 150\n"
      "  retries: 4\n"
      "  status_poll_ms: 30\n"
      "  values_poll_ms: 500\n"
      "  link_fault_after_ms: 2000\n"
      "  set_start_parameters: false\n"
      "  emulator:\n"
      "    min_hz: 50\n"
      "    max_hz: 600\n"
      "    ramp_up_hz_s: 300\n"
      "    ramp_down_hz_s: 500\n"
      "    converter_type: 4626\n"
      "    firmware: 0x0501\n"
      "    serial_number: 777\n"
      "    converter_hours: 12.5\n"
      "    motor_hours: 3\n"
      "    motor_code: 16\n"
      "    current_limit_a: 6.5\n"
      "    dc_link_voltage_v: 60\n";
  const auto s = parse(text);
  const auto e = emulator_of(text);
  EXPECT_EQ(s.port.port, "/dev/ttyUSB1");
  EXPECT_EQ(s.port.line.baud, 19200u);
  EXPECT_EQ(s.session.reply_timeout, 150ms);
  EXPECT_EQ(s.session.retries, 4u);
  EXPECT_EQ(s.session.status_poll, 30ms);
  EXPECT_EQ(s.session.values_poll, 500ms);
  EXPECT_EQ(s.session.link_fault_after, 2000ms);
  EXPECT_FALSE(s.session.set_start_parameters);
  EXPECT_DOUBLE_EQ(e.min_hz, 50.0);
  EXPECT_DOUBLE_EQ(e.max_hz, 600.0);
  EXPECT_DOUBLE_EQ(e.ramp_up_hz_s, 300.0);
  EXPECT_DOUBLE_EQ(e.ramp_down_hz_s, 500.0);
  EXPECT_EQ(e.converter_type, 4626);
  EXPECT_EQ(e.firmware, 0x0501);
  EXPECT_EQ(e.serial_number, 777u);
  EXPECT_DOUBLE_EQ(e.converter_hours, 12.5);
  EXPECT_DOUBLE_EQ(e.motor_hours, 3.0);
  EXPECT_EQ(e.motor_code, 16);
  EXPECT_DOUBLE_EQ(e.current_limit_a, 6.5);
  EXPECT_DOUBLE_EQ(e.dc_link_voltage_v, 60.0);
}

TEST(SpindleSection, RejectsMalformedInputWithItsPosition) {
  expect_config_error([] { (void)parse("spindle:\n  retrys: 3\n"); },
                      "cell.yaml:2:3: spindle.retrys: unknown field (did you mean 'retries'?)");
  expect_config_error([] { (void)parse("spindle:\n  status_poll_ms: 1\n"); },
                      "cell.yaml:2:19: spindle.status_poll_ms: 1 is out of range [5, 5000]");
  expect_config_error([] { (void)parse("spindle:\n  reply_timeout_ms: soon\n"); },
                      "cell.yaml:2:21: spindle.reply_timeout_ms: expected a whole number, got 'soon'");
  expect_config_error([] { (void)parse("spindle:\n  reply_timeout_ms: 500\n  link_fault_after_ms: 400\n"); },
                      "cell.yaml:3:24: spindle.link_fault_after_ms: link_fault_after_ms must be longer than "
                      "reply_timeout_ms");
  expect_config_error([] { (void)emulator_of("spindle:\n  emulator:\n    min_hz: 500\n    max_hz: 400\n"); },
                      "cell.yaml:4:13: spindle.emulator.max_hz: max_hz must be above min_hz");
  expect_config_error([] { (void)emulator_of("spindle:\n  emulator:\n    motor_code: 17\n"); },
                      "cell.yaml:3:17: spindle.emulator.motor_code: 17 is out of range [0, 16]");
  expect_config_error(
      [] { (void)emulator_of("spindle:\n  emulator:\n    ramp_up_hz: 400\n"); },
      "cell.yaml:3:5: spindle.emulator.ramp_up_hz: unknown field (did you mean 'ramp_up_hz_s'?)");
  expect_config_error([] { (void)parse("spindle:\n  parity: mark\n"); },
                      "cell.yaml:2:11: spindle.parity: 'mark' is not one of: none, even, odd");
}

TEST(SpindleSection, TheDefaultCellsSectionParses) {
  const auto root = YamlNode::load_file(CELLCTL_SOURCE_DIR "/config/cell.yaml");
  const auto s = parse_spindle_section(root.at("spindle"));
  EXPECT_TRUE(s.port.emulated());
  EXPECT_EQ(s.session.status_poll, 20ms);
  const auto e = emulation::parse_spindle_emulator(root.at("spindle"));
  EXPECT_EQ(e.converter_type, 4624);
  EXPECT_EQ(e.firmware, 0x0433);
}

}  // namespace
}  // namespace cellctl::config

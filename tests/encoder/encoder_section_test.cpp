// The `encoder:` config section: defaults, every key reaching its field, and exact
// file:line:column messages for the rules.
#include "config/encoder_section.hpp"

#include <gtest/gtest.h>

#include "emulation/emulator_setup.hpp"

namespace cellctl::config {
namespace {

EncoderSection parse(const std::string& text) {
  return parse_encoder_section(YamlNode::load_string(text, "cell.yaml").at("encoder"));
}
// The section's `emulator:` block, read where emulators are built.
encoder::EmulatorConfig emulator_of(const std::string& text) {
  const auto section = YamlNode::load_string(text, "cell.yaml").at("encoder");
  return emulation::parse_encoder_emulator(section, parse_encoder_section(section).session);
}

std::string error_of(const std::string& text) {
  try {
    (void)emulator_of(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(EncoderSection, FullSectionReachesSessionAndEmulator) {
  const std::string text =
      "encoder:\n"
      "  port: emulated\n"
      "  baud: 1500000\n"
      "  station_address: 5\n"
      "  master_address: 2\n"
      "  functionality: scancon3.0\n"
      "  code_sequence: ccw\n"
      "  scaling: true\n"
      "  measuring_units: 4096\n"
      "  total_range: 65536\n"
      "  units_select: per_revolution\n"
      "  commissioning: true\n"
      "  upper_limit: 60000\n"
      "  time_base: steps_per_10ms\n"
      "  mm_per_revolution: 4.0\n"
      "  watchdog_ms: 200\n"
      "  slot_time_bits: 400\n"
      "  retries: 2\n"
      "  lost_after_ms: 50\n"
      "  emulator:\n"
      "    singleturn_steps: 8192\n"
      "    revolutions: 4096\n"
      "    serial: 'SCH8800042'\n"
      "    state_file: /tmp/encoder.eeprom\n";
  const auto s = parse(text);
  const auto emulator = emulator_of(text);
  EXPECT_EQ(s.port.line.baud, 1500000u);
  EXPECT_EQ(s.port.line.parity, link::Parity::even);
  EXPECT_EQ(s.session.station_address, 5);
  EXPECT_EQ(s.session.bus.master_address, 2);
  EXPECT_EQ(s.session.parameters.functionality, encoder::Functionality::scancon30);
  EXPECT_EQ(s.session.parameters.code_sequence, encoder::CodeSequence::ccw);
  EXPECT_TRUE(s.session.parameters.scaling);
  EXPECT_TRUE(s.session.parameters.commissioning);
  EXPECT_TRUE(s.session.parameters.upper_limit_enabled);
  EXPECT_FALSE(s.session.parameters.lower_limit_enabled);
  EXPECT_EQ(s.session.parameters.upper_limit, 60000u);
  EXPECT_EQ(s.session.parameters.time_base, encoder::TimeBase::steps_per_10ms);
  EXPECT_DOUBLE_EQ(s.session.mm_per_revolution, 4.0);
  EXPECT_EQ(s.session.bus.wd_fact_1 * s.session.bus.wd_fact_2, 20);
  EXPECT_EQ(s.session.bus.slot_time_bits, 400u);
  EXPECT_EQ(s.session.bus.max_retries, 2);
  EXPECT_EQ(s.session.bus.lost_slave_time, std::chrono::milliseconds(50));
  EXPECT_EQ(s.session.bus.line.baud, 1500000u);
  EXPECT_EQ(emulator.address, 5);
  EXPECT_EQ(std::string(emulator.identity.serial.begin(), emulator.identity.serial.end()), "SCH8800042");
  EXPECT_EQ(emulator.state_file, "/tmp/encoder.eeprom");
}

TEST(EncoderSection, DefaultsAreProfibus8E1At19200) {
  const auto s = parse("encoder:\n  counts_per_mm: 2048\n");
  const auto emulator = emulator_of("encoder:\n  counts_per_mm: 2048\n");
  EXPECT_EQ(s.port.line.baud, 19200u);
  EXPECT_EQ(s.port.line.parity, link::Parity::even);
  EXPECT_EQ(s.session.parameters.functionality, encoder::Functionality::scancon22);
  EXPECT_EQ(emulator.identity.physical.total(), 1u << 25);
}

TEST(EncoderSection, ErrorsNameFileLineColumnFieldAndRule) {
  EXPECT_EQ(error_of("encoder:\n  counts_per_mm: 1\n  functionality: class3\n"),
            "cell.yaml:3:18: encoder.functionality: 'class3' is not one of: class1, class2, scancon2.1, "
            "scancon2.2, "
            "scancon3.0");
  EXPECT_EQ(
      error_of("encoder:\n  counts_per_mm: 1\n  watchdog_ms: 15\n"),
      "cell.yaml:3:16: encoder.watchdog_ms: must be a multiple of 10 ms (10 ms × WD_Fact_1 × WD_Fact_2)");
  EXPECT_EQ(error_of("encoder:\n  station_address: 1\n"),
            "cell.yaml:2:3: encoder: give exactly one of counts_per_mm and mm_per_revolution");
  EXPECT_EQ(
      error_of(
          "encoder:\n  counts_per_mm: 1\n  scaling: true\n  measuring_units: 3000\n  total_range: 3001\n"),
      "cell.yaml:2:3: encoder: parameters: Total Measuring Range: must be an integer multiple of the "
      "measuring "
      "units per revolution (4.1.3 rule 1) (value 3001, limit 3000)");
  EXPECT_EQ(
      error_of("encoder:\n  counts_per_mm: 1\n  without_status_bits: true\n"),
      "cell.yaml:3:24: encoder.without_status_bits: only with functionality scancon3.0 (manual 4.1.5 bit 4)");
  EXPECT_EQ(error_of("encoder:\n  counts_per_mm: 1\n  emulator:\n    serial: abc\n"),
            "cell.yaml:4:13: encoder.emulator.serial: must be 10 ASCII characters (manual 4.2.18)");
  EXPECT_NE(error_of("encoder:\n  counts_per_mm: 1\n  station_addres: 3\n").find("cell.yaml:3:3:"),
            std::string::npos);
  EXPECT_NE(
      error_of("encoder:\n  counts_per_mm: 1\n  emulator:\n    revolutions: 3000\n")
          .find("cell.yaml:4:18: encoder.emulator.revolutions: Number of Revolutions: must be a power of 2"),
      std::string::npos);
}

}  // namespace
}  // namespace cellctl::config

namespace cellctl::config {
namespace {

TEST(EncoderSection, DefaultCellYamlSectionLoads) {
  const auto s = parse_encoder_section(YamlNode::load_file(CELLCTL_CELL_YAML).at("encoder"));
  EXPECT_EQ(s.session.station_address, 5);
  EXPECT_EQ(s.session.parameters.functionality, encoder::Functionality::scancon22);
  EXPECT_TRUE(s.port.emulated());
}

}  // namespace
}  // namespace cellctl::config

#include "config/yaml_node.hpp"

#include <gtest/gtest.h>

#include "support/expect_config_error.hpp"

namespace cellctl::config {
namespace {

using cellctl::testing::expect_config_error;

TEST(YamlNode, ReadsTypedValues) {
  auto root = YamlNode::load_string("a: 12\nb: 1.5\nc: yes\nd: hello\ne: 0x3011\n", "t.yaml");
  EXPECT_EQ(root.at("a").as_int<int>(), 12);
  EXPECT_DOUBLE_EQ(root.at("b").as_double(), 1.5);
  EXPECT_TRUE(root.at("c").as_bool());
  EXPECT_EQ(root.string_at("d"), "hello");
  EXPECT_EQ(root.at("e").as_int<std::uint16_t>(), 0x3011);
  EXPECT_DOUBLE_EQ(root.double_in_or("missing", 0, 10, 7.0), 7.0);
}

TEST(YamlNode, ErrorsNameFileLineColumnFieldAndRule) {
  auto root = YamlNode::load_string("scu:\n  baud: fast\n  actuators:\n    - stroke_mm: -5\n", "cell.yaml");
  expect_config_error([&] { (void)root.at("scu").at("baud").as_integer(); },
                      "cell.yaml:2:9: scu.baud: expected a whole number, got 'fast'");
  expect_config_error(
      [&] { (void)root.at("scu").at("actuators").items()[0].double_in("stroke_mm", 1, 1000); },
      "cell.yaml:4:18: scu.actuators[0].stroke_mm: -5 is out of range [1, 1000]");
  expect_config_error([&] { (void)root.at("scu").at("speed"); },
                      "cell.yaml:2:3: scu: missing required field 'speed'");
}

TEST(YamlNode, MillisecondsAreWholeNumbersInRange) {
  using std::chrono::milliseconds;
  auto root = YamlNode::load_string("timeout_ms: 250\nbad_ms: 5000\nfrac_ms: 1.5\n", "t.yaml");
  EXPECT_EQ(root.milliseconds_or("timeout_ms", 10, 2000, milliseconds(7)), milliseconds(250));
  EXPECT_EQ(root.milliseconds_or("missing_ms", 10, 2000, milliseconds(7)), milliseconds(7));
  expect_config_error([&] { (void)root.milliseconds_or("bad_ms", 10, 2000, milliseconds(7)); },
                      "t.yaml:2:9: bad_ms: 5000 is out of range [10, 2000]");
  expect_config_error([&] { (void)root.milliseconds_or("frac_ms", 10, 2000, milliseconds(7)); },
                      "t.yaml:3:10: frac_ms: expected a whole number, got '1.5'");
}

TEST(YamlNode, SmallIntegersAreNumbersNotCharacters) {
  auto root = YamlNode::load_string("id: 300\nok: 7\n", "t.yaml");
  EXPECT_EQ(root.at("ok").as_int<std::uint8_t>(), 7);
  expect_config_error([&] { (void)root.at("id").as_int<std::uint8_t>(); },
                      "t.yaml:1:5: id: 300 is out of range [0, 255]");
}

TEST(YamlNode, UnknownKeysAreRejectedWithASuggestion) {
  auto root = YamlNode::load_string("speed: 1\nsped: 2\n", "r.yaml");
  expect_config_error(
      [&] {
        root.only_keys({"speed", "target"});
      },
      "r.yaml:2:1: sped: unknown field (did you mean 'speed'?)");
  auto other = YamlNode::load_string("colour: red\n", "r.yaml");
  expect_config_error([&] { other.only_keys({"speed"}); }, "r.yaml:1:1: colour: unknown field");
}

TEST(YamlNode, ChoicesAndParseErrors) {
  auto root = YamlNode::load_string("parity: mark\n", "p.yaml");
  expect_config_error(
      [&] {
        (void)root.at("parity").as_choice({"none", "even", "odd"});
      },
      "p.yaml:1:9: parity: 'mark' is not one of: none, even, odd");
  expect_config_error([] { (void)YamlNode::load_string("a: [1, 2\n", "bad.yaml"); },
                      "bad.yaml:2:1: invalid YAML: end of sequence flow not found");
}

TEST(YamlNode, EmptyValueIsNamed) {
  auto root = YamlNode::load_string("port:\n", "e.yaml");
  EXPECT_THROW((void)root.at("port"), ConfigError);
}

}  // namespace
}  // namespace cellctl::config

#include "config/yaml_node.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "config/yaml_structure.hpp"
#include "config/yaml_text.hpp"
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

TEST(YamlNode, NumbersBeyondAnyFieldAreOutOfRangeNotGarbage) {
  auto root = YamlNode::load_string("n: 99999999999999999999\nm: -1e999\nh: 0x-5\n", "t.yaml");
  expect_config_error([&] { (void)root.at("n").as_int<int>(); },
                      "t.yaml:1:4: n: 99999999999999999999 is out of range [-2147483648, 2147483647]");
  expect_config_error(
      [&] { (void)root.at("n").as_integer(); },
      "t.yaml:1:4: n: 99999999999999999999 is out of range [-9223372036854775808, 9223372036854775807]");
  expect_config_error([&] { (void)root.at("m").as_double_in(0, 10); },
                      "t.yaml:2:4: m: -1e999 is out of range [0, 10]");
  expect_config_error([&] { (void)root.at("h").as_integer(); },
                      "t.yaml:3:4: h: expected a whole number, got '0x-5'");
}

// yaml-cpp keeps one of two equal keys without a word; a cell or recipe with both is ambiguous.
TEST(YamlStructure, DuplicateKeysAreRefusedNamingBothPlaces) {
  expect_config_error(
      [] { (void)YamlNode::load_string("a: 1\nb:\n  c: 2\n  c: 3\n", "d.yaml"); },
      "d.yaml:4:3: b.c: duplicate key 'c': also given at line 3, column 3; which one is meant?");
  expect_config_error(
      [] { (void)YamlNode::load_string("x: [{p: 1, p: 2}]\n", "d.yaml"); },
      "d.yaml:1:12: x[0].p: duplicate key 'p': also given at line 1, column 6; which one is meant?");
  // The same key in sibling mappings is no duplicate; quoting does not make a different key.
  EXPECT_NO_THROW((void)YamlNode::load_string("a: {k: 1}\nb: {k: 1}\n", "d.yaml"));
  expect_config_error(
      [] { (void)YamlNode::load_string("k: 1\n'k': 2\n", "d.yaml"); },
      "d.yaml:2:1: k: duplicate key 'k': also given at line 1, column 1; which one is meant?");
}

TEST(YamlStructure, OneDocumentPerFile) {
  expect_config_error(
      [] { (void)YamlNode::load_string("a: 1\n---\nb: 2\n", "m.yaml"); },
      "m.yaml:2:1: a second YAML document starts here; a config or recipe file holds one document");
  EXPECT_NO_THROW((void)YamlNode::load_string("---\na: 1\n...\n", "m.yaml"));
}

TEST(YamlStructure, KeysArePlainNames) {
  expect_config_error([] { (void)YamlNode::load_string("? [a, b]\n: 1\n", "k.yaml"); },
                      "k.yaml:1:3: a key must be a plain name, not a list");
  expect_config_error([] { (void)YamlNode::load_string("{a: 1}: 2\n", "k.yaml"); },
                      "k.yaml:1:1: a key must be a plain name, not a mapping");
  expect_config_error([] { (void)YamlNode::load_string("s:\n  ~: 2\n", "k.yaml"); },
                      "k.yaml:2:3: s: a key must be a plain name, not null or empty");
  expect_config_error([] { (void)YamlNode::load_string("a: &n x\nb: {*n : 1}\n", "k.yaml"); },
                      "k.yaml:2:5: b: a key must be a plain name, not an alias");
}

TEST(YamlStructure, NestingDeeperThanTheLimitIsRefusedBeforeYamlCppRecursesFurther) {
  const auto nested = [](int depth) {
    return std::string(static_cast<std::size_t>(depth), '[') +
           std::string(static_cast<std::size_t>(depth), ']');
  };
  EXPECT_NO_THROW((void)YamlNode::load_string("a: " + nested(kMaxYamlNesting - 1) + "\n", "n.yaml"));
  expect_config_error(
      [&] { (void)YamlNode::load_string("a: " + nested(kMaxYamlNesting) + "\n", "n.yaml"); },
      "n.yaml:1:35: a[0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0][0]"
      "[0][0][0]: nested deeper than 32 levels");
  // A hundred thousand levels: refused at level 33, no stack overflow.
  EXPECT_THROW((void)YamlNode::load_string(nested(100'000), "n.yaml"), ConfigError);
}

TEST(YamlText, NulBytesAndInvalidUtf8AreRefusedWhereTheyAre) {
  expect_config_error([] { (void)YamlNode::load_string(std::string("a: 1\nb: x\0y\n", 12), "t.yaml"); },
                      "t.yaml:2:5: NUL byte: the file must be UTF-8 text (is it UTF-16 or binary?)");
  expect_config_error([] { (void)YamlNode::load_string("a: caf\xe9\n", "t.yaml"); },
                      "t.yaml:1:7: invalid UTF-8 (byte 0xE9): the file must be UTF-8 text");
  expect_config_error([] { (void)YamlNode::load_string("a: \xc0\xaf\n", "t.yaml"); },  // overlong '/'
                      "t.yaml:1:4: invalid UTF-8 (byte 0xC0): the file must be UTF-8 text");
  expect_config_error([] { (void)YamlNode::load_string("a: \xed\xa0\x80\n", "t.yaml"); },  // a surrogate
                      "t.yaml:1:4: invalid UTF-8 (byte 0xED): the file must be UTF-8 text");
  expect_config_error(
      [] { (void)YamlNode::load_string("a: \xf4\x90\x80\x80\n", "t.yaml"); },  // above U+10FFFF
      "t.yaml:1:4: invalid UTF-8 (byte 0xF4): the file must be UTF-8 text");
  expect_config_error([] { (void)YamlNode::load_string("a: \xe2\x82", "t.yaml"); },  // cut off
                      "t.yaml:1:4: invalid UTF-8 (byte 0xE2): the file must be UTF-8 text");
  EXPECT_EQ(YamlNode::load_string("a: café ±0.1 µm\n", "t.yaml").string_at("a"), "café ±0.1 µm");
}

// Each test reads from its own directory: nothing shared in /tmp with other tests or runs.
class YamlFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        std::filesystem::temp_directory_path() / fmt::format("cellctl-yaml-{}-{}", info->name(), ::getpid());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(YamlFile, ReadsARegularFile) {
  EXPECT_EQ(YamlNode::load_file(write("ok.yaml", "a: 5\n")).at("a").as_int<int>(), 5);
}

TEST_F(YamlFile, UnreadablePathsAreNamedWithTheReason) {
  const auto missing = (dir_ / "missing.yaml").string();
  expect_config_error([&] { (void)YamlNode::load_file(missing); },
                      missing + ":1:1: cannot read the file: No such file or directory");
  expect_config_error([&] { (void)YamlNode::load_file(dir_); },
                      dir_.string() + ":1:1: cannot read the file: it is a directory");
  expect_config_error(
      [] { (void)YamlNode::load_file("/dev/zero"); },
      "/dev/zero:1:1: cannot read the file: it is not a regular file (a device, a pipe or a socket)");
  const auto fifo = dir_ / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_config_error(
      [&] { (void)YamlNode::load_file(fifo); },  // no writer: must not hang
      fifo.string() + ":1:1: cannot read the file: it is not a regular file (a device, a pipe or a socket)");
}

TEST_F(YamlFile, AFileOverTheSizeLimitIsRefusedUnread) {
  const auto at_limit = write("at-limit.yaml", "a: 1\n#" + std::string(kMaxYamlFileBytes - 7, 'x') + "\n");
  EXPECT_EQ(std::filesystem::file_size(at_limit), kMaxYamlFileBytes);
  EXPECT_EQ(YamlNode::load_file(at_limit).at("a").as_int<int>(), 1);
  const auto over = write("over.yaml", std::string(kMaxYamlFileBytes + 1, '#'));
  expect_config_error(
      [&] { (void)YamlNode::load_file(over); },
      over.string() +
          ":1:1: cannot read the file: it is 1048577 bytes, over the limit of 1048576 bytes (1 MiB)");
}

}  // namespace
}  // namespace cellctl::config

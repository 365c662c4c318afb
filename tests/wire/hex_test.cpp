#include "wire/hex.hpp"

#include <gtest/gtest.h>

namespace cellctl::wire {
namespace {

TEST(Hex, FormatsLowercaseSpaced) {
  const std::vector<std::uint8_t> b{0x52, 0x4f, 0x00, 0xAB};
  EXPECT_EQ(to_hex(b), "52 4f 00 ab");
  EXPECT_EQ(to_hex({}), "");
}

TEST(Hex, ParsesWithAndWithoutSpaces) {
  EXPECT_EQ(parse_hex("52 4f 00"), (std::vector<std::uint8_t>{0x52, 0x4f, 0x00}));
  EXPECT_EQ(parse_hex("524F00"), (std::vector<std::uint8_t>{0x52, 0x4f, 0x00}));
  EXPECT_FALSE(parse_hex("524").has_value());
  EXPECT_FALSE(parse_hex("5g").has_value());
}

TEST(Hex, DigitValues) {
  EXPECT_EQ(hex_value('a'), 10);
  EXPECT_EQ(hex_value('F'), 15);
  EXPECT_EQ(hex_value('g'), -1);
  EXPECT_EQ(hex_digit(11), 'b');
}

}  // namespace
}  // namespace cellctl::wire

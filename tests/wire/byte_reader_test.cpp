#include "wire/byte_reader.hpp"

#include <gtest/gtest.h>

#include <array>

namespace cellctl::wire {
namespace {

TEST(ByteReader, ReadsLittleAndBigEndian) {
  const std::array<std::uint8_t, 8> bytes{0x39, 0x30, 0x00, 0x00, 0x00, 0xa7, 0xff, 0xfe};
  ByteReader r(bytes);
  EXPECT_EQ(r.le<std::int32_t>(), 12345);
  EXPECT_EQ(r.be<std::uint16_t>(), 0x00a7);
  EXPECT_EQ(r.be<std::int16_t>(), -2);
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.at_end());
}

TEST(ByteReader, NegativeLittleEndian) {
  const std::array<std::uint8_t, 4> bytes{0x38, 0xff, 0xff, 0xff};
  ByteReader r(bytes);
  EXPECT_EQ(r.le<std::int32_t>(), -200);
}

TEST(ByteReader, ReadingPastTheEndLatchesAndYieldsZero) {
  const std::array<std::uint8_t, 3> bytes{1, 2, 3};
  ByteReader r(bytes);
  EXPECT_EQ(r.u8(), 1);
  EXPECT_EQ(r.le<std::uint32_t>(), 0u);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.u8(), 0) << "once failed, stays failed";
  EXPECT_TRUE(r.bytes(1).empty());
}

TEST(ByteReader, BytesViewsWithoutCopy) {
  const std::array<std::uint8_t, 4> bytes{1, 2, 3, 4};
  ByteReader r(bytes);
  (void)r.u8();
  auto v = r.bytes(2);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v.data(), bytes.data() + 1);
  EXPECT_EQ(r.remaining(), 1u);
}

}  // namespace
}  // namespace cellctl::wire

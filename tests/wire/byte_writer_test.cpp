#include "wire/byte_writer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace cellctl::wire {
namespace {

TEST(ByteWriter, WritesBothEndiannesses) {
  std::array<std::uint8_t, 10> buf{};
  ByteWriter w(buf);
  w.le<std::int32_t>(-200);
  w.be<std::uint16_t>(0x0190);
  w.u8(0x52);
  ASSERT_TRUE(w.ok());
  const std::vector<std::uint8_t> got(w.written().begin(), w.written().end());
  EXPECT_EQ(got, (std::vector<std::uint8_t>{0x38, 0xff, 0xff, 0xff, 0x01, 0x90, 0x52}));
}

TEST(ByteWriter, OverflowWritesNothingAndLatches) {
  std::array<std::uint8_t, 3> buf{};
  ByteWriter w(buf);
  w.u8(1);
  w.le<std::uint32_t>(0xdeadbeef);
  EXPECT_FALSE(w.ok());
  EXPECT_EQ(w.size(), 1u);
  w.u8(2);
  EXPECT_EQ(w.size(), 1u);
}

TEST(ByteWriter, FloatRoundTripsThroughBits) {
  std::array<std::uint8_t, 4> buf{};
  ByteWriter w(buf);
  w.le_float(1.5f);
  EXPECT_EQ(buf, (std::array<std::uint8_t, 4>{0x00, 0x00, 0xc0, 0x3f}));
}

}  // namespace
}  // namespace cellctl::wire

#include "wire/byte_queue.hpp"

#include <gtest/gtest.h>

#include <array>

namespace cellctl::wire {
namespace {

TEST(ByteQueue, FifoAcrossTheWrap) {
  ByteQueue<4> q;
  const std::array<std::uint8_t, 3> a{1, 2, 3};
  EXPECT_EQ(q.push(a), 3u);
  q.drop(2);
  const std::array<std::uint8_t, 3> b{4, 5, 6};
  EXPECT_EQ(q.push(b), 3u);
  EXPECT_EQ(q.size(), 4u);
  EXPECT_EQ(q[0], 3);
  std::array<std::uint8_t, 8> out{};
  EXPECT_EQ(q.pop(out), 4u);
  EXPECT_EQ(out[0], 3);
  EXPECT_EQ(out[3], 6);
  EXPECT_TRUE(q.empty());
}

TEST(ByteQueue, RefusesWhenFull) {
  ByteQueue<2> q;
  const std::array<std::uint8_t, 3> a{1, 2, 3};
  EXPECT_EQ(q.push(a), 2u);
  EXPECT_EQ(q.free_space(), 0u);
}

}  // namespace
}  // namespace cellctl::wire

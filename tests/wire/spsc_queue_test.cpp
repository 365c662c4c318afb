#include "wire/spsc_queue.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace cellctl::wire {
namespace {

TEST(SpscQueue, FifoAndFull) {
  SpscQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(99)) << "full";
  EXPECT_EQ(q.pop(), 0);
  EXPECT_TRUE(q.push(4));
  for (int i = 1; i <= 4; ++i) EXPECT_EQ(q.pop(), i);
  EXPECT_FALSE(q.pop().has_value());
  EXPECT_TRUE(q.empty());
}

TEST(SpscQueue, TwoThreadsLoseNothingAndKeepOrder) {
  auto q = std::make_unique<SpscQueue<long, 64>>();
  constexpr long kCount = 200'000;
  std::thread producer([&] {
    for (long i = 0; i < kCount; ++i)
      while (!q->push(i)) std::this_thread::yield();
  });
  long expected = 0;
  while (expected < kCount) {
    if (auto v = q->pop()) {
      ASSERT_EQ(*v, expected);
      ++expected;
    }
  }
  producer.join();
}

}  // namespace
}  // namespace cellctl::wire

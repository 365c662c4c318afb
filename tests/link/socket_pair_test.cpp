// SocketPair, the in-process line of `cellctl run --emulate`: transparent for every byte value both
// ways, and — the reason it replaced the pseudo-terminal there — what one end writes is readable at
// the other end as soon as write() has returned, with no kernel worker in between (a pty's bytes
// wait for the tty flip-buffer worker, which a loaded machine kept off the CPU for 240 ms).

#include "link/socket_pair.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numeric>
#include <vector>

namespace cellctl::link {
namespace {

std::vector<std::uint8_t> every_byte_value() {
  std::vector<std::uint8_t> v(256);
  std::iota(v.begin(), v.end(), std::uint8_t{0});
  return v;
}

// One read, no waiting and no retry: what has arrived by now.
std::vector<std::uint8_t> read_now(Link& from) {
  std::array<std::uint8_t, 1024> buf{};
  const auto r = from.read(buf);
  EXPECT_TRUE(r.ok());
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count)};
}

TEST(SocketPair, EveryByteValueIsThereAtOnceBothWays) {
  SocketPair pair("test");
  const auto bytes = every_byte_value();
  ASSERT_EQ(pair.master().write(bytes).count, bytes.size());
  EXPECT_EQ(read_now(pair.device()), bytes) << "delivered by write(), not later";
  ASSERT_EQ(pair.device().write(bytes).count, bytes.size());
  EXPECT_EQ(read_now(pair.master()), bytes);
}

TEST(SocketPair, ReadsNothingWithoutWaitingWhenNothingCame) {
  SocketPair pair("test");
  EXPECT_TRUE(read_now(pair.master()).empty());
  EXPECT_TRUE(read_now(pair.device()).empty());
}

TEST(SocketPair, KeepsTelegramsInOrderAcrossWrites) {
  SocketPair pair("test");
  const std::vector<std::uint8_t> first{0x68, 0x05, 0x05, 0x68}, second{0x10, 0x7D, 0x02, 0x49, 0xC8, 0x16};
  ASSERT_EQ(pair.master().write(first).count, first.size());
  ASSERT_EQ(pair.master().write(second).count, second.size());
  auto expected = first;
  expected.insert(expected.end(), second.begin(), second.end());
  EXPECT_EQ(read_now(pair.device()), expected);
}

TEST(SocketPair, SaysWhichDeviceItCarries) {
  SocketPair pair("encoder");
  EXPECT_EQ(pair.master().describe(), "socketpair:encoder");
  EXPECT_EQ(pair.device().describe(), "socketpair:encoder:device");
}

}  // namespace
}  // namespace cellctl::link

#include "link/link_health.hpp"

#include <gtest/gtest.h>

namespace cellctl::link {
namespace {

using namespace std::chrono_literals;

TEST(LinkHealth, TracksRoundTripAndSilence) {
  LinkHealth h;
  const TimePoint t0{};
  EXPECT_EQ(h.silent_for(t0 + 50ms, t0), 50ms) << "silent since activation when nothing came yet";
  h.record_reply(t0 + 10ms, t0 + 14ms);
  h.record_reply(t0 + 20ms, t0 + 22ms);
  EXPECT_EQ(h.good_replies, 2u);
  EXPECT_EQ(h.last_round_trip, 2ms);
  EXPECT_EQ(h.max_round_trip, 4ms);
  EXPECT_EQ(h.max_silence, 8ms) << "from the first good reply to the second";
  h.record_reply(t0 + 25ms, t0 + 27ms);
  EXPECT_EQ(h.max_silence, 8ms) << "a shorter gap leaves the longest";
  EXPECT_EQ(h.silent_for(t0 + 100ms, t0), 73ms);
  EXPECT_EQ(h.silent_for(t0 + 100ms, t0 + 90ms), 10ms) << "a later activation restarts the count";
}

}  // namespace
}  // namespace cellctl::link

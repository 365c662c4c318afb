#include "command/order.hpp"

#include <gtest/gtest.h>

namespace cellctl::command {
namespace {

using namespace std::chrono_literals;

TEST(ParseUtc, ReadsRfc3339InUtcOnly) {
  const auto t = parse_utc("2026-11-27T19:50:00.125Z");
  ASSERT_TRUE(t);
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::milliseconds>(t->time_since_epoch()).count(),
            1'795'809'000'125LL);
  EXPECT_EQ(parse_utc("2026-11-27T19:50:00+00:00"), parse_utc("2026-11-27T19:50:00Z"));
  for (const char* bad : {"", "2026-11-27 19:50:00Z", "2026-11-27T19:50:00", "2026-11-27T19:50:00+01:00",
                          "2026-13-27T19:50:00Z", "2026-11-27T19:50:00.Z", "x026-11-27T19:50:00Z"})
    EXPECT_FALSE(parse_utc(bad)) << bad;
}

TEST(Expired, AFreshCommandIsNotAndAnOldOneSaysHowOld) {
  const auto now = std::chrono::steady_clock::now();
  const auto utc = std::chrono::system_clock::now();
  Order o{{}, now - 1999ms, std::nullopt};
  EXPECT_EQ(expired(o, now, utc, 2000ms), "");
  o.received = now - 2001ms;
  EXPECT_EQ(expired(o, now, utc, 2000ms),
            "expired: it waited 2001 ms here, more than the 2000 ms a command may (not obeyed)");
  o.received = now;
  o.issued_at = utc - 500ms;
  EXPECT_EQ(expired(o, now, utc, 2000ms), "");
  o.issued_at = utc - 2500ms;
  EXPECT_NE(expired(o, now, utc, 2000ms), "");
}

TEST(Capped, KeepsNamesShortAndPrintable) {
  EXPECT_EQ(capped("MES-7"), "MES-7");
  EXPECT_EQ(capped(std::string(1000, 'a'), 10), "aaaaaaaaaa…");
  EXPECT_EQ(capped("a\nb\x1b"), "a?b?");
  EXPECT_EQ(capped("ab\xc3\xa9", 3), "ab…");  // not cut inside the é
}

}  // namespace
}  // namespace cellctl::command

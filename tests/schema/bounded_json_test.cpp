// JSON from the network is bounded before it becomes a tree: the depth that once crashed the
// process (150 000 levels) is refused by a pass that builds nothing.
#include "schema/bounded_json.hpp"

#include <gtest/gtest.h>

namespace cellctl::schema {
namespace {

std::string nested(std::size_t depth) {
  return "{\"a\":" + std::string(depth - 1, '[') + std::string(depth - 1, ']') + "}";
}

TEST(BoundedJson, ACommandsPayloadIsParsed) {
  const auto r = parse_bounded_object(R"({"id":7,"by":"MES","issued_at":"2026-11-27T19:50:00Z"})");
  ASSERT_TRUE(std::holds_alternative<nlohmann::json>(r));
  EXPECT_EQ(std::get<nlohmann::json>(r)["id"], 7);
  EXPECT_EQ(std::get<nlohmann::json>(parse_bounded_object("")), nlohmann::json::object());
}

TEST(BoundedJson, DepthUpToTheLimitIsTakenBeyondItRefusedUnread) {
  EXPECT_TRUE(std::holds_alternative<nlohmann::json>(parse_bounded_object(nested(32))));
  const auto r = parse_bounded_object(nested(33));
  ASSERT_TRUE(std::holds_alternative<std::string>(r));
  EXPECT_EQ(std::get<std::string>(r), "the payload nests deeper than 32 levels: refused unread");
  // The depth that crashed the process, within the size limit and far beyond it.
  EXPECT_TRUE(std::holds_alternative<std::string>(parse_bounded_object(nested(30000))));
  EXPECT_TRUE(std::holds_alternative<std::string>(
      parse_bounded_object(nested(150000), {.max_bytes = 1 << 20, .max_depth = 32})));
}

TEST(BoundedJson, SizeIsCheckedBeforeAnythingIsRead) {
  const std::string big = "{\"a\":\"" + std::string(70000, 'x') + "\"}";
  const auto r = parse_bounded_object(big);
  ASSERT_TRUE(std::holds_alternative<std::string>(r));
  EXPECT_EQ(std::get<std::string>(r), "the payload is 70008 bytes, more than the 65536 a command may have");
}

TEST(BoundedJson, NoObjectAndNoJsonAreRefusedWithoutEchoingThem) {
  for (const char* bad : {"[1,2]", "7", "{\"a\":", "secret-token-not-json"}) {
    const auto r = parse_bounded_object(bad);
    ASSERT_TRUE(std::holds_alternative<std::string>(r)) << bad;
    EXPECT_EQ(std::get<std::string>(r).find(bad), std::string::npos);
  }
}

}  // namespace
}  // namespace cellctl::schema

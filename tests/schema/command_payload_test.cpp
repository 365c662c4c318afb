// A command's payload read at the edge: each field in its own type, the id echoed in its own kind, and
// the answer written back with the same id — the command desk sees typed fields only.
#include "schema/command_payload.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "schema/command_answer.hpp"

namespace cellctl::schema {
namespace {

CommandPayload read(std::string_view text) {
  auto r = read_command_payload(text);
  EXPECT_TRUE(std::holds_alternative<CommandPayload>(r)) << std::get<std::string>(r);
  return std::holds_alternative<CommandPayload>(r) ? std::get<CommandPayload>(r) : CommandPayload{};
}

std::string refusal(std::string_view text) {
  auto r = read_command_payload(text);
  EXPECT_TRUE(std::holds_alternative<std::string>(r)) << text;
  return std::holds_alternative<std::string>(r) ? std::get<std::string>(r) : std::string();
}

TEST(CommandPayload, EachFieldIsTakenInItsOwnTypeOnly) {
  const auto p = read(R"({"recipe":"demo","by":"MES","issued_at":"2026-11-28T10:00:00Z","axes":["x","z"],)"
                      R"("axis":"x","distance_mm":100,"from_mm":-5.5,"speed_mm_s":12})");
  EXPECT_EQ(p.recipe.value, "demo");
  EXPECT_EQ(p.by.value, "MES");
  EXPECT_EQ(p.issued_at.value, "2026-11-28T10:00:00Z");
  EXPECT_EQ(p.axes.value, (std::vector<std::string>{"x", "z"}));
  EXPECT_EQ(p.axis.value, "x");
  EXPECT_EQ(p.distance_mm.value, 100.0);
  EXPECT_EQ(p.from_mm.value, -5.5);
  EXPECT_EQ(p.speed_mm_s.value, 12.0);
  // Present in another type: given, without a value (the desk refuses it in the field's words).
  const auto q = read(R"({"recipe":7,"axes":["x",1],"distance_mm":"far","issued_at":12})");
  for (const bool given : {q.recipe.given, q.axes.given, q.distance_mm.given, q.issued_at.given})
    EXPECT_TRUE(given);
  EXPECT_FALSE(q.recipe.value || q.axes.value || q.distance_mm.value || q.issued_at.value);
  // Absent: neither.
  const auto none = read("");
  EXPECT_FALSE(none.recipe.given || none.axes.given || none.distance_mm.given || none.by.given);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(none.id));
}

TEST(CommandPayload, TheIdIsEchoedInItsOwnKind) {
  for (const char* text : {R"({"id":7})", R"({"id":-7})", R"({"id":7.5})", R"({"id":"job-41"})",
                           R"({"id":18446744073709551615})"}) {
    CommandAnswer a{"stop", read(text).id, true, "accepted", "", {}, false, {}, {}};
    const auto sent = nlohmann::json::parse(text);
    EXPECT_EQ(nlohmann::json::parse(answer_payload(a))["id"], sent["id"]) << text;
    EXPECT_EQ(answer_payload(a).find(sent["id"].dump()) != std::string::npos, true) << answer_payload(a);
  }
  EXPECT_TRUE(std::holds_alternative<std::monostate>(read(R"({"id":null})").id));
}

TEST(CommandPayload, AnIdThatCannotBeEchoedAsSentIsRefused) {
  const std::string why = "'id' must be a string of at most 128 characters or a number";
  EXPECT_EQ(refusal(R"({"id":{"job":41}})"), why);
  EXPECT_EQ(refusal(R"({"id":[41]})"), why);
  EXPECT_EQ(refusal(R"({"id":true})"), why);
  EXPECT_EQ(refusal("{\"id\":\"" + std::string(129, 'j') + "\"}"), why);
  (void)read("{\"id\":\"" + std::string(128, 'j') + "\"}");
}

TEST(CommandAnswer, ItsJsonHasTheFieldsItWasGiven) {
  CommandAnswer a{"start",
                  std::uint64_t{7},
                  false,
                  "recipe 'bad' is not valid",
                  "plant t/cmd/start",
                  1.25,
                  false,
                  3,
                  {"bad.yaml:3:5: speed: must be positive"}};
  EXPECT_EQ(answer_payload(a),
            R"({"command":"start","errors":["bad.yaml:3:5: speed: must be positive"],"exit":3,"id":7,)"
            R"("ok":false,"reason":"recipe 'bad' is not valid","source":"plant t/cmd/start","t":1.25})");
  CommandAnswer ok{"start", {}, true, "started", "", {}, true, {}, {}};
  EXPECT_EQ(answer_payload(ok), R"({"command":"start","ok":true,"outcome":"started","valid":true})");
}

}  // namespace
}  // namespace cellctl::schema

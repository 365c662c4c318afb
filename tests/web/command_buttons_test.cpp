// The page's buttons follow PackML's table: enabled exactly where the arbiter takes the command,
// disabled otherwise with the table's words; jobs start only under cellctl serve; an unknown state
// never disables Stop or Abort.
#include "web/command_buttons.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace cellctl::web {
namespace {

// The buttons as the board carries them (schema/page_payloads.hpp), read back.
nlohmann::json command_buttons(std::string_view state, bool starts_jobs) {
  schema::Board board;
  board.buttons = web::command_buttons(state, starts_jobs);
  return nlohmann::json::parse(schema::board_json(board))["buttons"];
}

bool enabled(const nlohmann::json& b, const char* cmd) {
  return b.at(cmd).at("enabled").get<bool>();
}

TEST(CommandButtons, ExecuteTakesHoldStopAbortAndNotUnholdClearOrAStart) {
  const auto b = command_buttons("Execute", true);
  EXPECT_TRUE(enabled(b, "hold"));
  EXPECT_TRUE(enabled(b, "stop"));
  EXPECT_TRUE(enabled(b, "abort"));
  EXPECT_FALSE(enabled(b, "unhold"));
  EXPECT_EQ(b["unhold"]["reason"], "unhold is taken only in Held or Holding");
  EXPECT_FALSE(enabled(b, "clear"));
  EXPECT_FALSE(enabled(b, "start"));
  EXPECT_EQ(b["start"]["reason"], "a job is in progress: Start is taken only in Idle");
  EXPECT_FALSE(b["hold"].contains("reason"));
}

TEST(CommandButtons, EveryStateAndCommandAgreesWithTheTable) {
  using supervisor::Command;
  for (int s = 0; s <= static_cast<int>(supervisor::State::clearing); ++s) {
    const auto state = static_cast<supervisor::State>(s);
    const auto name = supervisor::to_string(state);
    ASSERT_EQ(state_named(name), state) << name;
    const auto b = command_buttons(name, true);
    for (const auto c : {Command::hold, Command::unhold, Command::stop, Command::abort, Command::reset,
                         Command::clear, Command::start}) {
      const std::string word(supervisor::to_string(c));
      const auto refusal = supervisor::refusal(state, c);
      EXPECT_EQ(enabled(b, word.c_str()), refusal.empty()) << name << " " << word;
      if (!refusal.empty()) {
        EXPECT_EQ(b[word]["reason"], std::string(refusal)) << name << " " << word;
      }
    }
    EXPECT_EQ(b["home"], b["start"]);
    EXPECT_EQ(b["teach-in"], b["start"]);
  }
}

TEST(CommandButtons, OneRunStartsNoJobAndAnUnknownStateKeepsOnlyTheStops) {
  const auto one_run = command_buttons("Idle", false);
  EXPECT_FALSE(enabled(one_run, "start"));
  EXPECT_NE(one_run["home"]["reason"].get<std::string>().find("cellctl serve"), std::string::npos);
  const auto unknown = command_buttons("Sideways", true);
  EXPECT_FALSE(state_named("Sideways"));
  EXPECT_TRUE(enabled(unknown, "stop"));
  EXPECT_TRUE(enabled(unknown, "abort"));
  for (const auto* c : {"hold", "unhold", "reset", "clear", "start"}) EXPECT_FALSE(enabled(unknown, c)) << c;
}

}  // namespace
}  // namespace cellctl::web

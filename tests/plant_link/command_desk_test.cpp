// The command desk's own answers, the ones no run has to give: a start's validation (exit-3 reasons
// with file:line:column), names that are no recipe names, words that are no commands, no run at all.

#include "plant_link/command_desk.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "config/cell_config.hpp"

namespace cellctl::plant_link {
namespace {

// As `cellctl run` has it: one arbiter, whose job is the run (in state job_state_), and no start.
class CommandDeskTest : public ::testing::Test {
 protected:
  CommandDeskTest() {
    arbiter_.attach({[this] { return job_state_; },
                     [](command::Command, const command::CommandSource&) {
                       return Taken{Taken::How::by_run, {}};
                     }});
    (void)arbiter_.start(order(), [] { return Taken{Taken::How::done, "started"}; });
  }
  static command::Order order() {
    return {{command::CommandSource::Origin::plant, "t/cmd", {}}, std::chrono::steady_clock::now(), {}};
  }
  static RunAccess access_of(command::Arbiter& arbiter) {
    RunAccess a;
    a.arbiter = &arbiter;
    return a;
  }
  config::CellConfig cell_ =
      config::load_cell_config(std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  command::State job_state_ = command::State::idle;  // the run's board before its first cycle
  command::Arbiter arbiter_{std::chrono::seconds(2), {}};
  CommandDesk desk_{cell_, std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/cli", access_of(arbiter_),
                    std::chrono::seconds(1)};
  nlohmann::json submit(std::string_view word, std::string_view payload) {
    auto a = desk_.submit({word, payload, order().source, std::chrono::steady_clock::now(), std::nullopt},
                          "Execute");
    EXPECT_TRUE(a.has_value());
    // As the plant reads it on its response topic.
    return a ? nlohmann::json::parse(schema::answer_payload(*a)) : nlohmann::json();
  }
};

TEST_F(CommandDeskTest, AStartOfAnInvalidRecipeGivesItsProblemsAsCheckDoes) {
  const auto a = submit("start", R"({"recipe":"bad-recipe","id":7})");
  EXPECT_EQ(a["ok"], false);
  EXPECT_EQ(a["id"], 7);
  EXPECT_EQ(a["exit"], 3);
  ASSERT_FALSE(a["errors"].empty());
  EXPECT_NE(a["errors"][0].get<std::string>().find(
                "bad-recipe.yaml:13:15: steps[0].move.to.x: 250 is out of range"),
            std::string::npos)
      << a.dump();
}

TEST_F(CommandDeskTest, AValidStartIsRefusedWhileThisCellctlHasItsRun) {
  const auto a = submit("start", R"({"recipe":"short"})");
  EXPECT_EQ(a["ok"], false);
  EXPECT_EQ(a["valid"], true);
  EXPECT_NE(a["reason"].get<std::string>().find("is valid (6 steps)"), std::string::npos) << a.dump();
  EXPECT_NE(a["reason"].get<std::string>().find("state Execute"), std::string::npos) << a.dump();
}

TEST_F(CommandDeskTest, NamesWordsAndPayloadsThatAreNotCommandsAreRefused) {
  EXPECT_NE(
      submit("start", R"({"recipe":"../config/cell"})")["reason"].get<std::string>().find("no recipe name"),
      std::string::npos);
  EXPECT_NE(submit("start", R"({})")["reason"].get<std::string>().find("needs the recipe's name"),
            std::string::npos);
  EXPECT_NE(submit("jump", "")["reason"].get<std::string>().find("is not a command"), std::string::npos);
  EXPECT_NE(submit("hold", "not json")["reason"].get<std::string>().find("is no JSON"), std::string::npos);
  // The interlocks: no hold before the run executes.
  EXPECT_EQ(submit("hold", "")["reason"],
            "hold is not possible in state Idle: hold is taken only in Execute");
  // Bounded before parsed: too deep, too large; neither echoed.
  const std::string deep = "{\"a\":" + std::string(20000, '[') + std::string(20000, ']') + "}";
  EXPECT_NE(submit("hold", deep)["reason"].get<std::string>().find("nests deeper than 32 levels"),
            std::string::npos);
  const std::string big = "{\"by\":\"" + std::string(100000, 'x') + "\"}";
  const auto a = submit("stop", big);
  EXPECT_NE(a["reason"].get<std::string>().find("more than the 65536"), std::string::npos);
  EXPECT_LT(a.dump().size(), 400u) << "the payload was echoed";
}

TEST_F(CommandDeskTest, AStartTheStateRefusesCostsNoValidation) {
  job_state_ = command::State::execute;
  const auto a = submit("start", R"({"recipe":"bad-recipe"})");
  EXPECT_EQ(a["ok"], false);
  EXPECT_FALSE(a.contains("errors")) << "validated although the state refuses any start: " << a.dump();
  EXPECT_EQ(a["reason"],
            "start is not possible in state Execute: a job is in progress: Start is taken only in Idle");
  EXPECT_NE(a["source"].get<std::string>().find("plant t/cmd"), std::string::npos) << a.dump();
}

TEST_F(CommandDeskTest, RoutineStartsAreCheckedForShapeAndRefusedByAOneRunCellctl) {
  EXPECT_NE(submit("teach-in", R"({"distance_mm":100})")["reason"].get<std::string>().find("needs the axis"),
            std::string::npos);
  EXPECT_NE(submit("teach-in", R"({"axis":"x"})")["reason"].get<std::string>().find("needs the distance"),
            std::string::npos);
  EXPECT_NE(submit("teach-in", R"({"axis":"x","distance_mm":0})")["reason"].get<std::string>().find(
                "'distance_mm' must be a number from 0.1 to 10000"),
            std::string::npos);
  EXPECT_NE(submit("home", R"({"axes":"x"})")["reason"].get<std::string>().find("list of axis names"),
            std::string::npos);
  // Well formed, but this desk belongs to one run (no start): refused with what to use instead.
  const auto a = submit("home", R"({"axes":["x"]})");
  EXPECT_EQ(a["ok"], false);
  EXPECT_NE(a["reason"].get<std::string>().find("needs `cellctl serve`"), std::string::npos) << a.dump();
}

TEST_F(CommandDeskTest, AStandingControllerIsHandedTheCheckedStart) {
  std::vector<StartRequest> started;
  std::vector<std::string> started_by;
  command::Arbiter standby(std::chrono::seconds(2), {});  // no job yet: the cell is Idle
  RunAccess access = access_of(standby);
  access.start = [&](const StartRequest& r, const command::CommandSource& by) {
    started.push_back(r);
    started_by.push_back(by.words());
    return Taken{Taken::How::done, "started"};
  };
  CommandDesk desk(cell_, std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/cli", access,
                   std::chrono::seconds(1));
  const auto submit_to = [&](std::string_view word, std::string_view payload) {
    return desk
        .submit({word, payload, order().source, std::chrono::steady_clock::now(), std::nullopt}, "Idle")
        .value();
  };
  EXPECT_EQ(submit_to("start", R"({"recipe":"short"})").ok, true);
  EXPECT_EQ(submit_to("start", R"({"recipe":"short"})").ok, false);  // the job is starting
  standby.job_ended(command::State::complete);
  EXPECT_EQ(submit_to("start", R"({"recipe":"short"})").ok, false);  // Complete: reset first
  EXPECT_EQ(submit_to("reset", "").ok, true);
  EXPECT_EQ(submit_to("start", R"({"recipe":"bad-recipe"})").exit, 3);
  EXPECT_EQ(submit_to("teach-in", R"({"axis":"x","distance_mm":50,"from_mm":5})").ok, true);
  ASSERT_EQ(started.size(), 2u) << "an invalid recipe reached the controller";
  // Each job is started by whoever sent the start: its run's start says so.
  EXPECT_EQ(started_by, (std::vector<std::string>{order().source.words(), order().source.words()}));
  const auto& recipe = std::get<StartRecipe>(started[0]);
  EXPECT_EQ(recipe.name, "short");
  EXPECT_EQ(recipe.steps, 6u);
  const auto& teach = std::get<StartTeachIn>(started[1]);
  EXPECT_EQ(teach.axis, "x");
  EXPECT_EQ(teach.distance_mm, 50.0);
  EXPECT_EQ(teach.from_mm, 5.0);
  EXPECT_FALSE(teach.speed_mm_s);
}

}  // namespace
}  // namespace cellctl::plant_link

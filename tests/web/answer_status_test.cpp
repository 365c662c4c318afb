// The HTTP status of each kind of answer, from the words their sources give (the arbiter's and the
// age check's own, the page's, the command desk's as it writes them).
#include "web/answer_status.hpp"

#include <gtest/gtest.h>

#include <string>

#include "command/arbiter.hpp"
#include "plant_link/command_desk.hpp"
#include "web/hand_over.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;
using command::Taken;

schema::CommandAnswer refused(const std::string& reason) {
  return plant_link::answer("start", {}, false, reason);
}

command::Order fresh() {
  return {
      {command::CommandSource::Origin::web, "10.0.0.7:4242", "token"}, std::chrono::steady_clock::now(), {}};
}

TEST(AnswerStatus, TakenIs200) {
  EXPECT_EQ(answer_status(plant_link::answer("stop", {}, true, "accepted at t = 1.000 s")), 200);
}

TEST(AnswerStatus, TheArbitersRefusalsByTheStateAre409) {
  command::Arbiter arbiter(2000ms, {}, command::State::stopped);
  EXPECT_EQ(answer_status(refused(arbiter.start_refusal(fresh()))), 409);
  EXPECT_EQ(answer_status(refused(arbiter.command(command::Command::hold, fresh()).text)), 409);
  command::Arbiter aborted(2000ms, {}, command::State::aborted);
  EXPECT_EQ(answer_status(refused(aborted.command(command::Command::reset, fresh()).text)), 409);
  EXPECT_EQ(answer_status(refused("unhold refused: the fault's cause is still present")), 409);
  EXPECT_EQ(answer_status(refused("no start is taken: the scu safe state is UNKNOWN since the last job")),
            409);
}

TEST(AnswerStatus, ExpiredAndAbandonedCommandsAre410) {
  command::Arbiter arbiter(2000ms, {});
  auto old = fresh();
  old.received -= 3s;
  const auto late = arbiter.command(command::Command::stop, old);
  ASSERT_EQ(late.how, Taken::How::refused);
  EXPECT_EQ(answer_status(refused(late.text)), 410);
  auto ahead = fresh();
  ahead.issued_at = std::chrono::system_clock::now() + 1h;
  EXPECT_EQ(answer_status(refused(arbiter.start_refusal(ahead))), 410);
  EXPECT_EQ(answer_status(refused(std::string(kClientGone))), 410);
}

TEST(AnswerStatus, PayloadAndShapeProblems) {
  EXPECT_EQ(answer_status(refused("nested deeper than 32 levels (expected {\"id\":…} or nothing)")), 400);
  EXPECT_EQ(answer_status(refused("'jump' is not a command: hold, unhold, stop, abort, reset, clear")), 404);
  auto invalid =
      refused("recipe 'demo' is not valid for cell 'demo-cell': 2 problems (exit 3); nothing moved");
  invalid.exit = 3;
  EXPECT_EQ(answer_status(invalid), 422);
  EXPECT_EQ(answer_status(refused("teach-in needs the distance: {\"axis\":\"x\",\"distance_mm\":100}")), 422);
  EXPECT_EQ(answer_status(refused("the run gave no answer within 2000 ms: the outcome is unknown")), 504);
}

}  // namespace
}  // namespace cellctl::web

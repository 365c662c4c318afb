// A stop always gets through: once a start is taken, the job it began is queued (registered, not yet
// running: Starting), and a stop or an abort from then on is routed to that job — which cancels the
// queued start or stops it before any motion — never taken as a stop between jobs, which would leave
// the queued start to run.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "command/arbiter.hpp"

namespace cellctl::command {
namespace {

using namespace std::chrono_literals;
using How = Taken::How;

Order now_from_plant() {
  return {
      {CommandSource::Origin::plant, "plant/area1/cmd/stop", "MES-7"}, std::chrono::steady_clock::now(), {}};
}

struct QueuedStart {
  std::vector<Command> handed;      // what reached the job
  std::vector<std::string> states;  // what the arbiter entered itself
  Arbiter arbiter{2000ms, tell()};

  QueuedStart() {
    arbiter.attach({[] { return State::starting; },  // begun, waiting for the serving thread
                    [this](Command c, const CommandSource&) {
                      handed.push_back(c);
                      return Taken{How::done, "cancelled before it started"};
                    }});
    const auto started = arbiter.start(now_from_plant(), [] { return Taken{How::done, "started: home"}; });
    EXPECT_EQ(started.how, How::done);
  }
  Tell tell() {
    Tell t;
    t.state = [this](State, State to, const std::string&) { states.emplace_back(supervisor::to_string(to)); };
    return t;
  }
};

TEST(ArbiterStopRouting, AStopAfterAStartWasTakenGoesToThatJob) {
  for (const auto c : {Command::stop, Command::abort}) {
    QueuedStart cell;
    const auto taken = cell.arbiter.command(c, now_from_plant());
    EXPECT_EQ(taken.how, How::done) << supervisor::to_string(c);
    EXPECT_EQ(taken.text, "cancelled before it started");
    EXPECT_EQ(cell.handed, std::vector<Command>{c});
    EXPECT_TRUE(cell.states.empty()) << "taken as a stop between jobs: the queued start would still run";
    EXPECT_EQ(cell.arbiter.state(), State::starting);  // the job's until it ends
  }
}

TEST(ArbiterStopRouting, AStartQueuedBehindATakenStartIsRefusedWhileAStopStillGoesThrough) {
  QueuedStart cell;
  int second = 0;
  const auto again = cell.arbiter.start(now_from_plant(), [&] {
    ++second;
    return Taken{How::done, "started"};
  });
  EXPECT_EQ(again.how, How::refused);
  EXPECT_EQ(second, 0);
  EXPECT_EQ(cell.arbiter.command(Command::stop, now_from_plant()).how, How::done);
  EXPECT_EQ(cell.handed, std::vector<Command>{Command::stop});
}

}  // namespace
}  // namespace cellctl::command

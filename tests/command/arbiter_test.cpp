// The one command path: a start only in Idle, the way back to Idle after each end state, commands
// handed to the job in progress, expired and ignored commands never obeyed.
#include "command/arbiter.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cellctl::command {
namespace {

using namespace std::chrono_literals;
using How = Taken::How;

Order now_from(CommandSource::Origin o = CommandSource::Origin::web) {
  return {{o, "10.0.0.7:4242", "token #1"}, std::chrono::steady_clock::now(), std::nullopt};
}

struct Cell {
  std::vector<std::string> told;  // what the arbiter said between jobs
  State job_state = State::execute;
  std::vector<std::pair<Command, std::string>> handed;  // what reached the job
  Arbiter arbiter{2000ms, tell()};
  int begun = 0;

  Cell() {
    arbiter.attach({[this] { return job_state; },
                    [this](Command c, const CommandSource& s) {
                      handed.emplace_back(c, s.words());
                      return Taken{How::by_run, {}};
                    }});
  }
  Tell tell() {
    Tell t;
    t.command = [this](Command c, const CommandSource& s) {
      told.push_back(std::string(supervisor::to_string(c)) + " by " + s.words());
    };
    t.state = [this](State from, State to, const std::string&) {
      told.push_back(std::string(supervisor::to_string(from)) + "->" +
                     std::string(supervisor::to_string(to)));
    };
    t.note = [this](const std::string& n) { told.push_back("note: " + n); };
    return t;
  }
  Taken start() {
    return arbiter.start(now_from(), [this] {
      ++begun;
      return Taken{How::done, "started"};
    });
  }
};

TEST(Arbiter, AStartIsTakenInIdleAndTheJobThenOwnsTheState) {
  Cell cell;
  EXPECT_EQ(cell.arbiter.start_refusal(now_from()), "");
  EXPECT_EQ(cell.start().how, How::done);
  EXPECT_EQ(cell.begun, 1);
  EXPECT_EQ(cell.arbiter.state(), State::execute);  // the job's
  const auto second = cell.start();
  EXPECT_EQ(second.how, How::refused);
  EXPECT_EQ(second.text,
            "start is not possible in state Execute: a job is in progress: Start is taken only in Idle");
  EXPECT_EQ(cell.begun, 1);
}

TEST(Arbiter, CommandsGoToTheJobWithTheirSourceWhenTheStateTakesThem) {
  Cell cell;
  ASSERT_EQ(cell.start().how, How::done);
  EXPECT_EQ(cell.arbiter.command(Command::hold, now_from()).how, How::by_run);
  const auto unhold = cell.arbiter.command(Command::unhold, now_from());  // Execute: refused here
  EXPECT_EQ(unhold.how, How::refused);
  EXPECT_EQ(unhold.text, "unhold is not possible in state Execute: unhold is taken only in Held or Holding");
  ASSERT_EQ(cell.handed.size(), 1u);
  EXPECT_EQ(cell.handed[0].first, Command::hold);
  EXPECT_EQ(cell.handed[0].second, "web 10.0.0.7:4242 (token #1)");
}

TEST(Arbiter, CompleteAndStoppedNeedAResetBeforeTheNextStart) {
  for (const auto end : {State::complete, State::stopped}) {
    Cell cell;
    ASSERT_EQ(cell.start().how, How::done);
    cell.arbiter.job_ended(end);
    const auto refused = cell.start();
    EXPECT_EQ(refused.how, How::refused) << supervisor::to_string(end);
    EXPECT_NE(refused.text.find("reset first"), std::string::npos) << refused.text;
    EXPECT_EQ(cell.arbiter.command(Command::reset, now_from()).how, How::done);
    EXPECT_EQ(cell.arbiter.state(), State::idle);
    EXPECT_EQ(cell.start().how, How::done);
    EXPECT_EQ(cell.begun, 2);
    const std::vector<std::string> told{"reset by web 10.0.0.7:4242 (token #1)",
                                        std::string(supervisor::to_string(end)) + "->Resetting",
                                        "Resetting->Idle"};
    EXPECT_EQ(cell.told, told);
  }
}

TEST(Arbiter, AbortedNeedsClearThenReset) {
  Cell cell;
  ASSERT_EQ(cell.start().how, How::done);
  cell.arbiter.job_ended(State::aborted);
  EXPECT_EQ(cell.start().how, How::refused);
  EXPECT_EQ(cell.arbiter.command(Command::reset, now_from()).how, How::refused);
  EXPECT_EQ(cell.arbiter.command(Command::clear, now_from()).how, How::done);
  EXPECT_EQ(cell.arbiter.state(), State::stopped);
  EXPECT_EQ(cell.start().how, How::refused);
  EXPECT_EQ(cell.arbiter.command(Command::reset, now_from()).how, How::done);
  EXPECT_EQ(cell.start().how, How::done);
  EXPECT_EQ(cell.handed.size(), 0u);  // none of it reached a job
}

TEST(Arbiter, AStopBetweenJobsLeavesTheCellStoppedUntilReset) {
  Cell cell;
  EXPECT_EQ(cell.arbiter.command(Command::stop, now_from()).how, How::done);
  EXPECT_EQ(cell.arbiter.state(), State::stopped);
  EXPECT_EQ(cell.start().how, How::refused);
  EXPECT_EQ(cell.arbiter.command(Command::hold, now_from()).how, How::refused);
}

TEST(Arbiter, AnExpiredCommandIsNotObeyed) {
  Cell cell;
  ASSERT_EQ(cell.start().how, How::done);
  auto old = now_from();
  old.received -= 2500ms;  // waited in some queue
  const auto stop = cell.arbiter.command(Command::stop, old);
  EXPECT_EQ(stop.how, How::refused);
  EXPECT_EQ(stop.text.rfind("stop expired: it waited ", 0), 0u) << stop.text;
  auto issued = now_from();
  issued.issued_at = std::chrono::system_clock::now() - 3s;  // stamped long ago by its sender
  EXPECT_EQ(cell.arbiter.command(Command::hold, issued).how, How::refused);
  issued.issued_at = std::chrono::system_clock::now() + 1h;  // a clock far ahead: its age is unknown
  EXPECT_EQ(cell.arbiter.command(Command::hold, issued).how, How::refused);
  EXPECT_TRUE(cell.handed.empty());
  EXPECT_EQ(cell.arbiter.counters().expired, 3u);  // the third's age is unknowable: not meant now either
  EXPECT_EQ(cell.arbiter.counters().refused, 3u);

  Cell idle;
  auto late_start = now_from();
  late_start.received -= 13s;  // the start that waited for the web readers to leave
  EXPECT_NE(idle.arbiter.start_refusal(late_start), "");
  EXPECT_EQ(idle.arbiter.start(late_start, [] { return Taken{How::done, "started"}; }).how, How::refused);
}

TEST(Arbiter, AnIgnoredMessageIsToldAndCountedAndNothingElse) {
  Cell cell;
  cell.arbiter.ignore("a retained start from the broker was ignored");
  EXPECT_EQ(cell.told, std::vector<std::string>{"note: a retained start from the broker was ignored"});
  EXPECT_EQ(cell.arbiter.counters().ignored, 1u);
  EXPECT_EQ(cell.arbiter.state(), State::idle);
  EXPECT_EQ(cell.begun, 0);
}

}  // namespace
}  // namespace cellctl::command

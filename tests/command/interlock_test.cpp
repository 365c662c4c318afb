// PackML's interlocks, as the README's state table gives them: every state against every command.
#include <gtest/gtest.h>

#include "supervisor/packml.hpp"

namespace cellctl::supervisor {
namespace {

// The README's table ("Which command each state takes"), written out: Y taken, - refused.
// Columns: start hold unhold stop abort reset clear.
struct Row {
  State state;
  const char* takes;
};
constexpr Row kTable[] = {
    {State::idle, "Y--YY--"},      {State::starting, "---YYY-"},   {State::execute, "-Y-YYY-"},
    {State::holding, "--YYYY-"},   {State::held, "--YYYY-"},       {State::unholding, "-Y-YYY-"},
    {State::stopping, "----Y--"},  {State::stopped, "----YY-"},    {State::aborting, "-------"},
    {State::aborted, "------Y"},   {State::completing, "---YYY-"}, {State::complete, "----YY-"},
    {State::resetting, "----Y--"}, {State::clearing, "-------"},
};

TEST(Interlock, EveryStateTakesExactlyTheCommandsOfTheTable) {
  for (const auto& row : kTable)
    for (std::size_t c = 0; c < kCommands; ++c) {
      const auto cmd = static_cast<Command>(c);
      const bool taken = refusal(row.state, cmd).empty();
      EXPECT_EQ(taken, row.takes[c] == 'Y')
          << to_string(cmd) << " in " << to_string(row.state) << ": " << refusal(row.state, cmd);
    }
}

TEST(Interlock, StartIsTakenOnlyInIdleAndTheRefusalSaysTheWayThere) {
  EXPECT_EQ(refusal(State::complete, Command::start), "reset first: Start is taken only in Idle");
  EXPECT_EQ(refusal(State::stopped, Command::start), "reset first: Start is taken only in Idle");
  EXPECT_EQ(refusal(State::aborted, Command::start), "clear, then reset: Start is taken only in Idle");
  EXPECT_EQ(refusal(State::aborted, Command::reset), "clear first: Aborted takes Clear, then Reset");
}

}  // namespace
}  // namespace cellctl::supervisor

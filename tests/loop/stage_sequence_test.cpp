#include <gtest/gtest.h>

#include <array>

#include "loop/stage_times.hpp"

namespace cellctl::loop {
namespace {

using namespace std::chrono_literals;

TEST(StageSequence, EachBoundaryEndsOneStageAndStartsTheNext) {
  link::VirtualClock clock;
  const std::array<std::string_view, 3> names{"read", "decide", "write"};
  StageTimes times(clock, names);
  {
    StageSequence seq(times);
    clock.advance(5us);  // before the first stage: not counted
    seq.begin(0);
    clock.advance(100us);
    seq.begin(1);
    clock.advance(30us);
    seq.begin(2);
    clock.advance(7us);
  }  // the last stage ends with the sequence
  EXPECT_EQ(times.histogram(0).total(), 100us);
  EXPECT_EQ(times.histogram(1).total(), 30us);
  EXPECT_EQ(times.histogram(2).total(), 7us);
  EXPECT_EQ(times.histogram(2).count(), 1u);
}

TEST(StageSequence, AnEmptySequenceRecordsNothing) {
  link::VirtualClock clock;
  const std::array<std::string_view, 1> names{"only"};
  StageTimes times(clock, names);
  { StageSequence seq(times); }
  EXPECT_EQ(times.histogram(0).count(), 0u);
}

}  // namespace
}  // namespace cellctl::loop

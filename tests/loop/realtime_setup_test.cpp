#include "loop/realtime_setup.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

namespace cellctl::loop {
namespace {

// These run on the test's own thread and restore what they change. mlockall is not exercised here:
// under the sanitizers it would try to lock their terabyte-sized shadow mappings.

TEST(RealtimeSetup, NothingRequestedTouchesNothing) {
  const RealtimeReport r = apply_realtime({});
  EXPECT_EQ(r.scheduler.outcome, RealtimeOutcome::not_requested);
  EXPECT_EQ(r.memory_lock.outcome, RealtimeOutcome::not_requested);
  EXPECT_EQ(r.affinity.outcome, RealtimeOutcome::not_requested);
  EXPECT_TRUE(r.warnings().empty());
}

TEST(RealtimeSetup, ConfigErrorsNameFieldAndValue) {
  try {
    (void)apply_realtime({.fifo_priority = 120});
    FAIL() << "expected a config error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "realtime.fifo_priority: must be 0..99, got 120");
  }
  EXPECT_THROW((void)apply_realtime({.cpu = -2}), std::invalid_argument);
}

TEST(RealtimeSetup, AffinityToAMissingCpuIsRefusedWithAReason) {
  const RealtimeReport r = apply_realtime({.cpu = CPU_SETSIZE - 1});
  EXPECT_EQ(r.affinity.outcome, RealtimeOutcome::refused);
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_NE(r.warnings()[0].find("affinity to CPU"), std::string::npos) << r.warnings()[0];
  EXPECT_NE(r.summary().find("affinity refused"), std::string::npos) << r.summary();
}

TEST(RealtimeSetup, AffinityToTheCurrentCpuIsObtained) {
  cpu_set_t saved;
  ASSERT_EQ(sched_getaffinity(0, sizeof(saved), &saved), 0);
  const RealtimeReport r = apply_realtime({.cpu = sched_getcpu()});
  EXPECT_EQ(r.affinity.outcome, RealtimeOutcome::obtained) << r.affinity.detail;
  ASSERT_EQ(sched_setaffinity(0, sizeof(saved), &saved), 0);
}

TEST(RealtimeSetup, FifoIsObtainedOrRefusedNeverFatal) {
  int policy = 0;
  sched_param saved{};
  ASSERT_EQ(pthread_getschedparam(pthread_self(), &policy, &saved), 0);
  const RealtimeReport r = apply_realtime({.fifo_priority = 10});
  ASSERT_NE(r.scheduler.outcome, RealtimeOutcome::not_requested);
  EXPECT_NE(r.scheduler.detail.find("SCHED_FIFO priority 10"), std::string::npos) << r.scheduler.detail;
  if (r.scheduler.outcome == RealtimeOutcome::obtained) {
    int now_policy = 0;
    sched_param now{};
    ASSERT_EQ(pthread_getschedparam(pthread_self(), &now_policy, &now), 0);
    EXPECT_EQ(now_policy, SCHED_FIFO);
    ASSERT_EQ(pthread_setschedparam(pthread_self(), policy, &saved), 0);
  } else {
    EXPECT_EQ(r.warnings().size(), 1u);
  }
}

// What a scope obtained is given back at its end: the scheduler (when SCHED_FIFO was permitted) and
// the CPU affinity (always permitted for the thread's own CPU).
TEST(RealtimeSetup, AScopePutsTheThreadBackAsItWas) {
  int policy = 0;
  sched_param param{};
  ASSERT_EQ(pthread_getschedparam(pthread_self(), &policy, &param), 0);
  cpu_set_t before;
  ASSERT_EQ(sched_getaffinity(0, sizeof(before), &before), 0);
  const int cpu = sched_getcpu();
  {
    const RealtimeScope scope({.fifo_priority = 10, .cpu = cpu});
    EXPECT_EQ(scope.report().affinity.outcome, RealtimeOutcome::obtained) << scope.report().affinity.detail;
    cpu_set_t inside;
    ASSERT_EQ(sched_getaffinity(0, sizeof(inside), &inside), 0);
    EXPECT_EQ(CPU_COUNT(&inside), 1);
    int inside_policy = 0;
    sched_param inside_param{};
    ASSERT_EQ(pthread_getschedparam(pthread_self(), &inside_policy, &inside_param), 0);
    if (scope.report().scheduler.outcome == RealtimeOutcome::obtained) {
      EXPECT_EQ(inside_policy, SCHED_FIFO);
    }
  }
  cpu_set_t after;
  ASSERT_EQ(sched_getaffinity(0, sizeof(after), &after), 0);
  EXPECT_TRUE(CPU_EQUAL(&before, &after))
      << CPU_COUNT(&before) << " CPUs before, " << CPU_COUNT(&after) << " after";
  int after_policy = 0;
  sched_param after_param{};
  ASSERT_EQ(pthread_getschedparam(pthread_self(), &after_policy, &after_param), 0);
  EXPECT_EQ(after_policy, policy);
  EXPECT_EQ(after_param.sched_priority, param.sched_priority);
}

}  // namespace
}  // namespace cellctl::loop

#include "loop/realtime_setup.hpp"

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace cellctl::loop {
namespace {

RealtimeItem refused(std::string what, int error) {
  return {RealtimeOutcome::refused,
          fmt::format("{} refused: {} ({})", what, std::strerror(error),
                      error == EPERM    ? "needs CAP_SYS_NICE / root or an rtprio limit"
                      : error == ENOMEM ? "RLIMIT_MEMLOCK too low?"
                                        : "see errno")};
}

RealtimeItem set_fifo(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  // pthread_setschedparam returns the error instead of setting errno.
  if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); err != 0) {
    return refused(fmt::format("SCHED_FIFO priority {}", priority), err);
  }
  return {RealtimeOutcome::obtained, fmt::format("SCHED_FIFO priority {}", priority)};
}

RealtimeItem lock_memory() {
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) return refused("mlockall(MCL_CURRENT|MCL_FUTURE)", errno);
  return {RealtimeOutcome::obtained, "memory locked (mlockall current and future)"};
}

RealtimeItem pin_to(int cpu) {
  if (cpu >= CPU_SETSIZE) return refused(fmt::format("affinity to CPU {}", cpu), EINVAL);
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<std::size_t>(cpu), &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0)
    return refused(fmt::format("affinity to CPU {}", cpu), errno);
  return {RealtimeOutcome::obtained, fmt::format("pinned to CPU {}", cpu)};
}

const char* word(RealtimeOutcome o) {
  switch (o) {
    case RealtimeOutcome::not_requested:
      return "not requested";
    case RealtimeOutcome::obtained:
      return "obtained";
    case RealtimeOutcome::refused:
      return "refused";
  }
  return "?";
}

}  // namespace

RealtimeReport apply_realtime(const RealtimeConfig& config) {
  if (config.fifo_priority < 0 || config.fifo_priority > 99) {
    throw std::invalid_argument(
        fmt::format("realtime.fifo_priority: must be 0..99, got {}", config.fifo_priority));
  }
  if (config.cpu < -1)
    throw std::invalid_argument(fmt::format("realtime.cpu: must be >= -1, got {}", config.cpu));
  RealtimeReport report;
  if (config.fifo_priority > 0) report.scheduler = set_fifo(config.fifo_priority);
  if (config.lock_memory) report.memory_lock = lock_memory();
  if (config.cpu >= 0) report.affinity = pin_to(config.cpu);
  return report;
}

RealtimeScope::RealtimeScope(const RealtimeConfig& config) : owner_(pthread_self()) {
  // What to go back to: read before anything is changed (both calls only read the calling thread, which
  // they cannot fail to do).
  (void)pthread_getschedparam(pthread_self(), &policy_, &param_);
  CPU_ZERO(&cpus_);
  (void)sched_getaffinity(0, sizeof(cpus_), &cpus_);
  report_ = apply_realtime(config);
}

RealtimeScope::~RealtimeScope() {
  const bool own_thread = pthread_equal(owner_, pthread_self()) != 0;
  // Going back asks for less than was obtained: refused all the same, a destructor has nothing better
  // to do than leave the thread as it is (the process is ending its real-time work).
  if (own_thread && report_.scheduler.outcome == RealtimeOutcome::obtained)
    (void)pthread_setschedparam(pthread_self(), policy_, &param_);
  if (own_thread && report_.affinity.outcome == RealtimeOutcome::obtained)
    (void)sched_setaffinity(0, sizeof(cpus_), &cpus_);
  if (report_.memory_lock.outcome == RealtimeOutcome::obtained) (void)munlockall();
}

std::vector<std::string> RealtimeReport::warnings() const {
  std::vector<std::string> out;
  for (const RealtimeItem* item : {&scheduler, &memory_lock, &affinity}) {
    if (item->outcome == RealtimeOutcome::refused) out.push_back(item->detail + "; the loop runs without it");
  }
  return out;
}

std::string RealtimeReport::summary() const {
  return fmt::format("real-time: scheduler {}, memory lock {}, affinity {}", word(scheduler.outcome),
                     word(memory_lock.outcome), word(affinity.outcome));
}

}  // namespace cellctl::loop

#pragma once
// Optional real-time set-up of the thread that will run the loop: SCHED_FIFO priority, locked memory
// (no page faults in the cycle), CPU affinity. Each is attempted only when configured; when the
// system refuses (no CAP_SYS_NICE, RLIMIT_MEMLOCK, no such CPU) the report says so and why, and the
// caller logs it and goes on: lack of privileges never stops the controller.

#include <pthread.h>
#include <sched.h>

#include <string>
#include <vector>

namespace cellctl::loop {

struct RealtimeConfig {
  int fifo_priority = 0;     // 1..99: SCHED_FIFO at that priority; 0: leave the scheduler alone
  bool lock_memory = false;  // mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;              // >= 0: pin the calling thread to that CPU; -1: leave it
};

enum class RealtimeOutcome { not_requested, obtained, refused };

struct RealtimeItem {
  RealtimeOutcome outcome = RealtimeOutcome::not_requested;
  std::string detail;  // what was obtained, or why it was refused
};

struct RealtimeReport {
  RealtimeItem scheduler;
  RealtimeItem memory_lock;
  RealtimeItem affinity;

  // One line per refused item, ready to log as a warning.
  [[nodiscard]] std::vector<std::string> warnings() const;
  // One line: what was obtained, refused and not requested.
  [[nodiscard]] std::string summary() const;
};

// Validates first: throws std::invalid_argument naming the field and value when fifo_priority is not
// in 0..99 or cpu < -1 (config errors). Then applies each configured item to the calling thread.
[[nodiscard]] RealtimeReport apply_realtime(const RealtimeConfig& config);

// apply_realtime for as long as the scope lives; at its end the calling thread's scheduler and CPU
// affinity are put back as they were and the memory unlocked, as far as they had been obtained. A
// controller that stands by between jobs (`cellctl serve`) must not keep real-time priority while it
// only waits. The scheduler and affinity are the thread's: a scope that ends on another thread
// leaves them (and says nothing, being a destructor). The memory lock is the process's: its end
// unlocks all of it, so one scope at a time (one run at a time, as serve runs jobs).
class RealtimeScope {
 public:
  explicit RealtimeScope(const RealtimeConfig& config);
  ~RealtimeScope();
  RealtimeScope(const RealtimeScope&) = delete;
  RealtimeScope& operator=(const RealtimeScope&) = delete;

  [[nodiscard]] const RealtimeReport& report() const noexcept { return report_; }

 private:
  pthread_t owner_;
  int policy_ = 0;
  sched_param param_{};
  cpu_set_t cpus_{};
  RealtimeReport report_;
};

}  // namespace cellctl::loop

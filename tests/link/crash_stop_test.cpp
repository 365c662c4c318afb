// The crash stop in a child process: armed ports get their telegrams when the process dies of a
// fatal signal, a disarmed one gets nothing, and the process still dies of that signal. Also a stack
// overflow (the alternate stack) and abort().
#include "link/crash_stop.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace cellctl::link {
namespace {

struct Pipe {
  int r = -1, w = -1;
  Pipe() {
    int fds[2];
    if (::pipe(fds) == 0) {
      r = fds[0];
      w = fds[1];
    }
  }
  ~Pipe() {
    if (r >= 0) ::close(r);
    if (w >= 0) ::close(w);
  }
  // Everything written until every writer is closed.
  std::vector<std::uint8_t> drain() {
    ::close(w);
    w = -1;
    std::vector<std::uint8_t> out;
    std::array<std::uint8_t, 256> buf{};
    for (ssize_t n; (n = ::read(r, buf.data(), buf.size())) > 0;)
      out.insert(out.end(), buf.begin(), buf.begin() + n);
    return out;
  }
};

// Recursion without end on purpose: the stack overflow that the crash stop must survive (g++ 12 says
// so at -O0, the dev preset, as an error).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winfinite-recursion"
[[gnu::noinline]] int overflow(int depth) {
  volatile char pad[4096];  // NOLINT: a frame the optimiser cannot drop
  pad[0] = static_cast<char>(depth);
  return overflow(depth + 1) + pad[0];
}
#pragma GCC diagnostic pop

// Forks; the child arms the pipes and dies as `die` makes it; returns the child's wait status.
template <class Die>
int child_dies(Pipe& scu, Pipe& spindle, Pipe& closed, Die die) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    crash_stop::install_handlers();
    const std::uint8_t f20[] = {0x52, 0x45, 0x13, 0xff, 0xff, 0x01, 0x02};
    const std::uint8_t stopp[] = {0x02, 0x30, 0x31, 0x61, 0x31, 0x03};
    (void)crash_stop::arm(scu.w, f20);
    (void)crash_stop::arm(spindle.w, stopp);
    crash_stop::disarm(crash_stop::arm(closed.w, f20));  // a port closed before the crash
    die();
    std::_Exit(0);  // not reached
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

void expect_stops_written(int status, int sig, Pipe& scu, Pipe& spindle, Pipe& closed) {
  EXPECT_TRUE(WIFSIGNALED(status)) << "the process did not die of its signal: status " << status;
  if (WIFSIGNALED(status)) {
    EXPECT_EQ(WTERMSIG(status), sig);
  }
  EXPECT_EQ(scu.drain(), (std::vector<std::uint8_t>{0x52, 0x45, 0x13, 0xff, 0xff, 0x01, 0x02}));
  EXPECT_EQ(spindle.drain(), (std::vector<std::uint8_t>{0x02, 0x30, 0x31, 0x61, 0x31, 0x03}));
  EXPECT_TRUE(closed.drain().empty()) << "a disarmed port was written to";
}

TEST(CrashStop, ASegvWritesEveryArmedPortsStopAndStillDies) {
  Pipe scu, spindle, closed;
  const int status = child_dies(scu, spindle, closed, [] { ::raise(SIGSEGV); });
  expect_stops_written(status, SIGSEGV, scu, spindle, closed);
}

TEST(CrashStop, AnAbortToo) {
  Pipe scu, spindle, closed;
  const int status = child_dies(scu, spindle, closed, [] { std::abort(); });
  expect_stops_written(status, SIGABRT, scu, spindle, closed);
}

TEST(CrashStop, AStackOverflowOnTheMainThreadToo) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reports a stack overflow itself (its own handler on its own stack)";
#endif
  Pipe scu, spindle, closed;
  const int status = child_dies(scu, spindle, closed, [] { (void)overflow(0); });
  expect_stops_written(status, SIGSEGV, scu, spindle, closed);
}

TEST(CrashStop, ATelegramTooLongOrSlotsFullArmsNothing) {
  const std::vector<std::uint8_t> long_one(crash_stop::kMaxTelegram + 1, 0x55);
  EXPECT_EQ(crash_stop::arm(1, long_one), -1);
  std::vector<int> slots;
  const std::uint8_t t[] = {1};
  for (std::size_t i = 0; i < crash_stop::kSlots; ++i) slots.push_back(crash_stop::arm(-1, t));
  EXPECT_EQ(crash_stop::arm(-1, t), -1);
  for (const int s : slots) crash_stop::disarm(s);
  const int again = crash_stop::arm(-1, t);
  EXPECT_GE(again, 0);
  crash_stop::disarm(again);
}

}  // namespace
}  // namespace cellctl::link

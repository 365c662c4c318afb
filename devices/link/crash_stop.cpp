#include "link/crash_stop.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <mutex>

namespace cellctl::link::crash_stop {
namespace {

struct Slot {
  std::atomic<bool> taken{false};  // owned by an arm() until disarm()
  std::atomic<int> fd{-1};         // published last: the handler writes only where this is set
  std::array<std::uint8_t, kMaxTelegram> bytes{};
  std::size_t size = 0;
};

std::array<Slot, kSlots> g_slots;
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);

void write_all(int fd, const std::uint8_t* p, std::size_t n) noexcept {
  // A few tries only: a port that does not take the bytes must not keep a dying process alive.
  for (int tries = 0; n > 0 && tries < 8; ++tries) {
    const ssize_t w = ::write(fd, p, n);
    if (w > 0) {
      p += w;
      n -= static_cast<std::size_t>(w);
    }
  }
}

void on_fatal_signal(int sig) {
  for (const auto& s : g_slots) {
    const int fd = s.fd.load(std::memory_order_acquire);
    if (fd >= 0) write_all(fd, s.bytes.data(), s.size);
  }
  // SA_RESETHAND gave the signal its default action back: die of it, as the process would have.
  ::raise(sig);
}

}  // namespace

int arm(int fd, std::span<const std::uint8_t> telegram) noexcept {
  if (telegram.size() > kMaxTelegram || telegram.empty()) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (!g_slots[i].taken.compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_slots[i].bytes.data(), telegram.data(), telegram.size());
    g_slots[i].size = telegram.size();
    g_slots[i].fd.store(fd, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void rearm(int slot, int fd) noexcept {
  if (slot >= 0 && static_cast<std::size_t>(slot) < kSlots)
    g_slots[static_cast<std::size_t>(slot)].fd.store(fd, std::memory_order_release);
}

void disarm(int slot) noexcept {
  if (slot < 0 || static_cast<std::size_t>(slot) >= kSlots) return;
  auto& s = g_slots[static_cast<std::size_t>(slot)];
  s.fd.store(-1, std::memory_order_release);
  s.taken.store(false);
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Its own stack: the handler must run after a stack overflow too. Never freed (the process's).
    static std::array<char, 64 * 1024> alt_stack;
    stack_t ss{};
    ss.ss_sp = alt_stack.data();
    ss.ss_size = alt_stack.size();
    // Best effort, as all of this: should the kernel refuse, a crash leaves the stops to the devices'
    // own protection where they have one (the SCU's communication time-out, the encoder's watchdog;
    // the spindle converter has none).
    (void)::sigaltstack(&ss, nullptr);
    struct sigaction sa {};
    sa.sa_handler = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = static_cast<int>(SA_ONSTACK | SA_RESETHAND | SA_NODEFER);
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) (void)::sigaction(sig, &sa, nullptr);
  });
}

}  // namespace cellctl::link::crash_stop

#pragma once
// What a crashed controller still does: on a fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT)
// the process writes each open device port's stop telegram — encoded in advance by the device's
// session, when the port was armed — with write(2) only, then dies of the signal as it would have.
// The spindle converter has no communication watchdog: without this, a crash leaves it turning.
//
// Async-signal-safe by construction: the handler reads fixed slots (atomics and plain bytes written
// before the slot's descriptor is published), calls write(2) and nothing else, on an alternate signal
// stack (a stack overflow is a SIGSEGV too). What it cannot do: stop a device whose line is cut, or
// one behind a process that is killed outright (SIGKILL, power loss) — a wired emergency stop is
// outside software. A telegram half written by the crashed process when the signal came may garble
// the one that follows; each device resynchronises on its own framing (manual-defined start and CRC).

#include <cstddef>
#include <cstdint>
#include <span>

namespace cellctl::link::crash_stop {

inline constexpr std::size_t kSlots = 8;
inline constexpr std::size_t kMaxTelegram = 32;

// Arms `fd` with `telegram`: written to it on a fatal signal. Returns the slot, or -1 when every slot
// is taken or the telegram is longer than kMaxTelegram (the caller's mistake; nothing is armed).
[[nodiscard]] int arm(int fd, std::span<const std::uint8_t> telegram) noexcept;
// The slot's port was opened again under another descriptor (or closed: -1).
void rearm(int slot, int fd) noexcept;
// The port is closing: nothing is written to it any more. A negative slot is ignored.
void disarm(int slot) noexcept;

// Installs the handlers (once per process; later calls do nothing). Call early in main().
void install_handlers();

}  // namespace cellctl::link::crash_stop

#pragma once
// A Link that puts faults on the line on purpose, on the injected clock: it wraps the session's end
// of a link (a SimLink's master end, or the SerialLink to an emulator's pseudo-terminal) and, while a
// scheduled fault window is open, makes the line silent, pulls the cable, flips bits, mixes in random
// bytes or holds the device's replies back. Between windows every byte passes unchanged.
//
// Deterministic: the bits flipped and the garbage injected come from a seeded generator and the
// windows from the clock, so a virtual-time run with the same faults is the same run.
//
// Port loss (disconnect) is what SerialLink reports when the tty's other side is gone: reads and
// writes answer IoStatus::closed with EIO, and what the device sends meanwhile is lost. A real
// failure of the wrapped link is never hidden: every read passes it on whatever the window says (a
// silent or disconnected window does not write to the wrapped link at all).
//
// No allocation after construction; read() and write() never wait.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <string>

#include "link/clock.hpp"
#include "link/link.hpp"
#include "link/link_fault.hpp"
#include "link/timed_byte_queue.hpp"

namespace cellctl::link {

class FaultInjectingLink final : public Link {
 public:
  static constexpr std::size_t kMaxWindows = 8;
  // Of `corrupt`: every kCorruptStride-th byte of the stream gets one (seeded) bit flipped, so any
  // telegram of at least that many octets fails its checksum or its framing. (A PROFIBUS short
  // acknowledge, one octet, is hit one time in four: then it is not E5 and the reply is missed.)
  static constexpr std::size_t kCorruptStride = 4;

  FaultInjectingLink(Link& inner, const Clock& clock, std::uint32_t seed = 1) noexcept;

  // The fault acts from `from` until `until` (for ever without one). Windows are looked at in the
  // order given; the first open one acts. False when kMaxWindows are scheduled already.
  [[nodiscard]] bool schedule(LinkFault fault, TimePoint from,
                              std::optional<TimePoint> until = std::nullopt) noexcept;
  // The fault acting at `now`, if any.
  [[nodiscard]] std::optional<LinkFault> active(TimePoint now) const noexcept;

  IoResult read(std::span<std::uint8_t> buffer) override;
  IoResult write(std::span<const std::uint8_t> bytes) override;
  [[nodiscard]] std::string describe() const override { return inner_.describe(); }
  void arm_crash_stop(std::span<const std::uint8_t> telegram) noexcept override {
    inner_.arm_crash_stop(telegram);
  }
  // While a disconnect window is open the port stays gone (closed); otherwise the wrapped link's.
  IoResult reopen() override;

  // What the faults have done so far (for tests and reports).
  struct Counters {
    std::uint64_t lost = 0;      // bytes discarded (silent, disconnect) in either direction
    std::uint64_t flipped = 0;   // bytes with a bit flipped
    std::uint64_t injected = 0;  // garbage bytes added
    std::uint64_t delayed = 0;   // bytes held back
  };
  [[nodiscard]] const Counters& counters() const noexcept { return counters_; }

 private:
  struct Window {
    LinkFault fault;
    TimePoint from;
    std::optional<TimePoint> until;
  };
  // Which way bytes go, for the state each direction keeps of its own.
  struct Direction {
    std::size_t corrupt_phase = 0;  // bytes since the last flipped one, modulo kCorruptStride
    TimePoint next_garbage{};
  };

  // Reads what the inner link has and throws it away; the inner link's failure, if any.
  IoResult discard_inbound();
  // Moves what the inner link has into the delay line, each byte due at `due`.
  IoResult hold_inbound(TimePoint due, bool delaying);
  void corrupt(std::span<std::uint8_t> bytes, Direction& d) noexcept;
  // A burst of random bytes when one is due (else none); returns how many were written to `out`.
  std::size_t garbage(std::span<std::uint8_t> out, Direction& d, TimePoint now) noexcept;

  Link& inner_;
  const Clock& clock_;
  std::minstd_rand rng_;
  std::array<Window, kMaxWindows> windows_{};
  std::size_t window_count_ = 0;
  TimedByteQueue<4096> delayed_;
  Direction inbound_;
  Direction outbound_;
  std::array<std::uint8_t, 512> scratch_{};
  Counters counters_;
};

}  // namespace cellctl::link

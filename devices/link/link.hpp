#pragma once
// A non-blocking byte transport. read() returns what has arrived (possibly nothing) and write()
// takes what the transport can take now; neither ever waits. Telegram boundaries are the codecs'
// business, not the link's.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace cellctl::link {

enum class IoStatus {
  ok,      // count bytes moved (0 is a normal answer: nothing there, or no room now)
  closed,  // the peer went away (pty closed, USB adapter unplugged)
  failed,  // an OS error; error_number says which
};

struct [[nodiscard]] IoResult {
  std::size_t count = 0;
  IoStatus status = IoStatus::ok;
  int error_number = 0;

  [[nodiscard]] bool ok() const noexcept { return status == IoStatus::ok; }
};

class Link {
 public:
  virtual ~Link() = default;
  virtual IoResult read(std::span<std::uint8_t> buffer) = 0;
  virtual IoResult write(std::span<const std::uint8_t> bytes) = 0;
  // Where this link goes, for messages and traces ("/dev/ttyUSB0", "sim:scu").
  [[nodiscard]] virtual std::string describe() const = 0;
  // After the link answered IoStatus::closed or failed: opens the same port again (a USB adapter that
  // came back, a pty published again at its symlink). ok() when the link can be used again; a link
  // with nothing to open (an in-memory line) is always ok. May make system calls and allocate: for the
  // safe-stop after a fault, never for the cycle of a healthy run.
  virtual IoResult reopen() { return {}; }
  // A stop telegram to write to this port should the process die of a fatal signal (crash_stop.hpp).
  // Only a link to a real port (a serial line, a pseudo-terminal) arms it: an in-memory line dies with
  // the process and the emulator behind it.
  virtual void arm_crash_stop(std::span<const std::uint8_t> /*telegram*/) noexcept {}
};

}  // namespace cellctl::link

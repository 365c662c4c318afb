#pragma once
// An in-process line between a session and its emulator without a tty: a connected pair of
// AF_UNIX stream sockets. What one end writes is in the other end's receive queue when write()
// returns, and read() takes it at once.
//
// Why not a pseudo-terminal: a pty hands its bytes to the reader through the tty flip buffer,
// whose work (flush_to_ldisc) runs on a normal-priority kernel worker of the unbound workqueue.
// Neither the real-time control loop nor the real-time emulator thread can lend that worker their
// priority, and a loaded 2-core machine has been measured (ftrace, issue 9) to keep it off the CPU
// for 240 ms — both directions of every pty at once — longer than the encoder's lost_after_ms
// (100 ms): the DP master lost an encoder that had answered in time. A socket has no such worker.
// So the emulators of `cellctl run` (in this process) sit on socket pairs; `cellctl emulate`,
// whose devices other programs open as serial ports, keeps its pseudo-terminals.

#include <memory>
#include <string>

#include "link/link.hpp"

namespace cellctl::link {

class SocketPair {
 public:
  // Throws LinkError when the sockets cannot be had.
  explicit SocketPair(const std::string& name);

  // The session's end and the emulator's end; each closes its socket when the pair goes.
  [[nodiscard]] Link& master() noexcept { return *master_; }
  [[nodiscard]] Link& device() noexcept { return *device_; }

 private:
  std::unique_ptr<Link> master_;
  std::unique_ptr<Link> device_;
};

}  // namespace cellctl::link

#include "link/fd_io.hpp"

#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>

namespace cellctl::link {

IoResult fd_read(int fd, std::span<std::uint8_t> buffer) noexcept {
  // Only read what the tty already holds. A read() that finds a tty's buffer empty first waits for
  // the kernel's flip-buffer worker to finish (n_tty_read → flush_work): a normal-priority kernel
  // thread that a loaded machine may keep off the CPU for tens or hundreds of milliseconds — and the
  // SCHED_FIFO control loop (or emulator thread) would wait with it, a priority inversion that lost
  // the encoder on a loaded 2-core machine. FIONREAD counts the bytes the line discipline holds
  // without waiting for anybody; bytes the worker has not delivered yet arrive at a later poll, as
  // they would on a slower line. A hung-up tty (pty closed, adapter unplugged) answers FIONREAD
  // with EIO.
  int available = 0;
  if (::ioctl(fd, FIONREAD, &available) != 0) {
    if (errno == EIO) return {0, IoStatus::closed, errno};
    if (errno != ENOTTY && errno != EINVAL) return {0, IoStatus::failed, errno};
    available = static_cast<int>(buffer.size());  // no tty: read() does not wait for a worker
  }
  if (available <= 0) return {0};
  if (static_cast<std::size_t>(available) < buffer.size())
    buffer = buffer.first(static_cast<std::size_t>(available));
  const ssize_t n = ::read(fd, buffer.data(), buffer.size());
  if (n >= 0) return {static_cast<std::size_t>(n)};
  if (errno == EAGAIN || errno == EINTR) return {0};
  // EIO is what a tty answers when its other side has gone (pty closed, adapter unplugged).
  if (errno == EIO) return {0, IoStatus::closed, errno};
  return {0, IoStatus::failed, errno};
}

IoResult fd_write(int fd, std::span<const std::uint8_t> bytes) noexcept {
  const ssize_t n = ::write(fd, bytes.data(), bytes.size());
  if (n >= 0) return {static_cast<std::size_t>(n)};
  if (errno == EAGAIN || errno == EINTR) return {0};
  if (errno == EIO) return {0, IoStatus::closed, errno};
  return {0, IoStatus::failed, errno};
}

bool make_raw(int fd) noexcept {
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) return false;
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS);
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  return tcsetattr(fd, TCSANOW, &tio) == 0;
}

}  // namespace cellctl::link

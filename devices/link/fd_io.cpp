#include "link/fd_io.hpp"

#include <termios.h>
#include <unistd.h>

#include <cerrno>

namespace cellctl::link {

IoResult fd_read(int fd, std::span<std::uint8_t> buffer) noexcept {
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

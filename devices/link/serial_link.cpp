#include "link/serial_link.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "link/crash_stop.hpp"
#include "link/fd_io.hpp"
#include "link/link_error.hpp"

namespace cellctl::link {
namespace {

speed_t speed_for(std::uint32_t baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1500000:
      return B1500000;
    case 2000000:
      return B2000000;
    default:
      return 0;
  }
}

[[noreturn]] void fail(int fd, const std::string& message, int cause = 0) {
  if (fd >= 0) ::close(fd);
  throw LinkError(message, cause);
}

std::string open_failure(const std::string& path, int err) {
  switch (err) {
    case ENOENT:
      return fmt::format("serial port {} does not exist", path);
    case EACCES:
      return fmt::format("no permission to open serial port {} (is this user in group dialout?)", path);
    case EBUSY:
      return fmt::format("serial port {} is in use by another process", path);
    default:
      return fmt::format("cannot open serial port {}: {}", path, std::strerror(err));
  }
}

// A pseudo-terminal has no UART, so its framing is nominal; and Linux refuses (EINVAL) a parity
// setting on a pty that was asked for parity before and did not keep it. A pty gets the speed and
// 8 data bits only. (Unix98 pty slaves are character devices with majors 136..143.)
bool is_pseudo_terminal(int fd) {
  struct stat st {};
  return fstat(fd, &st) == 0 && S_ISCHR(st.st_mode) && major(st.st_rdev) >= 136 && major(st.st_rdev) <= 143;
}

void configure_line(int fd, const std::string& path, LineFormat format) {
  const speed_t speed = speed_for(format.baud);
  if (speed == 0) fail(fd, fmt::format("serial port {}: baud rate {} is not supported", path, format.baud));
  if (format.data_bits < 5 || format.data_bits > 8 || format.stop_bits < 1 || format.stop_bits > 2)
    fail(fd, fmt::format("serial port {}: framing {} is not supported", path, format.describe()));
  if (!make_raw(fd)) fail(fd, fmt::format("{} is not a serial port: {}", path, std::strerror(errno)));

  termios tio{};
  tcgetattr(fd, &tio);
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | PARODD | CSTOPB);
  static constexpr tcflag_t kSize[] = {CS5, CS6, CS7, CS8};
  tio.c_cflag |= kSize[format.data_bits - 5];
  if (!is_pseudo_terminal(fd)) {
    if (format.parity != Parity::none) tio.c_cflag |= PARENB;
    if (format.parity == Parity::odd) tio.c_cflag |= PARODD;
    if (format.stop_bits == 2) tio.c_cflag |= CSTOPB;
  }
  if (tcsetattr(fd, TCSANOW, &tio) != 0)
    fail(fd, fmt::format("serial port {}: cannot set {}: {}", path, format.describe(), std::strerror(errno)));
}

}  // namespace

std::unique_ptr<SerialLink> SerialLink::open(const std::string& path, LineFormat format) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    throw LinkError(open_failure(path, err), err);
  }
  // flock also holds against root, which TIOCEXCL does not.
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) fail(fd, open_failure(path, EBUSY), EBUSY);
  ioctl(fd, TIOCEXCL);
  configure_line(fd, path, format);

  int lines = TIOCM_DTR | TIOCM_RTS;
  const bool held = ioctl(fd, TIOCMBIS, &lines) == 0;
  if (!held && errno != ENOTTY && errno != EINVAL)
    fail(fd, fmt::format("serial port {}: cannot raise DTR/RTS: {}", path, std::strerror(errno)));
  tcflush(fd, TCIOFLUSH);  // nothing stale from before we owned the port
  return std::unique_ptr<SerialLink>(new SerialLink(fd, path, format, held));
}

SerialLink::~SerialLink() {
  crash_stop::disarm(crash_slot_);  // before the descriptor can be reused by anything else
  if (fd_ >= 0) ::close(fd_);
}

void SerialLink::arm_crash_stop(std::span<const std::uint8_t> telegram) noexcept {
  crash_stop::disarm(crash_slot_);
  crash_slot_ = crash_stop::arm(fd_, telegram);
}

IoResult SerialLink::reopen() {
  // The old descriptor goes first: its lock would refuse the new one.
  crash_stop::rearm(crash_slot_, -1);
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  try {
    auto fresh = open(path_, format_);
    std::swap(fd_, fresh->fd_);
    modem_lines_held_ = fresh->modem_lines_held_;
    crash_stop::rearm(crash_slot_, fd_);
    return {};
  } catch (const LinkError& e) {
    return {0, IoStatus::closed, e.cause()};
  }
}

IoResult SerialLink::read(std::span<std::uint8_t> buffer) {
  if (fd_ < 0) return {0, IoStatus::closed, EBADF};
  return fd_read(fd_, buffer);
}
IoResult SerialLink::write(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) return {0, IoStatus::closed, EBADF};
  return fd_write(fd_, bytes);
}
std::string SerialLink::describe() const {
  return fmt::format("{} ({})", path_, format_.describe());
}

}  // namespace cellctl::link

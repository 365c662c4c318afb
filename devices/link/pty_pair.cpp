#include "link/pty_pair.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "link/fd_io.hpp"
#include "link/link_error.hpp"

namespace cellctl::link {

PtyPair::PtyPair(std::string name, std::optional<std::filesystem::path> symlink) {
  device_.name = std::move(name);
  device_.fd = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (device_.fd < 0)
    throw LinkError(fmt::format("cannot create a pseudo-terminal: {}", std::strerror(errno)));
  char buf[128];
  if (grantpt(device_.fd) != 0 || unlockpt(device_.fd) != 0 || ptsname_r(device_.fd, buf, sizeof buf) != 0) {
    const int err = errno;
    ::close(device_.fd);
    throw LinkError(fmt::format("cannot set up a pseudo-terminal: {}", std::strerror(err)));
  }
  peer_path_ = buf;
  held_peer_fd_ = ::open(peer_path_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  // Raw from the start: before a client sets its own mode, the line discipline must neither echo the
  // emulator's bytes back to it nor act on 0x03 or 0x11/0x13 in binary telegrams.
  if (held_peer_fd_ < 0 || !make_raw(held_peer_fd_)) {
    const int err = errno;
    if (held_peer_fd_ >= 0) ::close(held_peer_fd_);
    ::close(device_.fd);
    throw LinkError(fmt::format("cannot open pseudo-terminal {}: {}", peer_path_, std::strerror(err)));
  }
  if (symlink) {
    std::error_code ec;
    const auto status = std::filesystem::symlink_status(*symlink, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_symlink(status)) {
      ::close(held_peer_fd_);
      ::close(device_.fd);
      throw LinkError(
          fmt::format("{} exists and is not a symlink; refusing to replace it", symlink->string()));
    }
    std::filesystem::remove(*symlink, ec);
    std::filesystem::create_symlink(peer_path_, *symlink, ec);
    if (ec) {
      ::close(held_peer_fd_);
      ::close(device_.fd);
      throw LinkError(
          fmt::format("cannot publish {} as {}: {}", peer_path_, symlink->string(), ec.message()));
    }
    symlink_ = std::move(symlink);
  }
}

PtyPair::~PtyPair() {
  if (symlink_) {
    std::error_code ec;
    std::filesystem::remove(*symlink_, ec);
  }
  ::close(held_peer_fd_);
  ::close(device_.fd);
}

IoResult PtyPair::MasterSide::read(std::span<std::uint8_t> buffer) {
  return fd_read(fd, buffer);
}
IoResult PtyPair::MasterSide::write(std::span<const std::uint8_t> bytes) {
  return fd_write(fd, bytes);
}

}  // namespace cellctl::link

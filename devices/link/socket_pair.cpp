#include "link/socket_pair.hpp"

#include <fmt/format.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "link/link_error.hpp"

namespace cellctl::link {
namespace {

// Both calls are non-blocking by flag; a peer that has gone is `closed` (EOF, EPIPE, ECONNRESET),
// never a SIGPIPE.
IoResult map_error(int err) noexcept {
  if (err == EAGAIN || err == EWOULDBLOCK || err == EINTR) return {0};
  if (err == EPIPE || err == ECONNRESET) return {0, IoStatus::closed, err};
  return {0, IoStatus::failed, err};
}

// One end of the pair; owns its socket.
class SocketEnd final : public Link {
 public:
  SocketEnd(int fd, std::string name) noexcept : fd_(fd), name_(std::move(name)) {}
  ~SocketEnd() override { ::close(fd_); }
  SocketEnd(const SocketEnd&) = delete;
  SocketEnd& operator=(const SocketEnd&) = delete;

  IoResult read(std::span<std::uint8_t> buffer) override {
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n > 0) return {static_cast<std::size_t>(n)};
    if (n == 0) return buffer.empty() ? IoResult{0} : IoResult{0, IoStatus::closed, 0};
    return map_error(errno);
  }
  IoResult write(std::span<const std::uint8_t> bytes) override {
    const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n >= 0) return {static_cast<std::size_t>(n)};
    return map_error(errno);
  }
  [[nodiscard]] std::string describe() const override { return name_; }

 private:
  int fd_;
  std::string name_;
};

}  // namespace

SocketPair::SocketPair(const std::string& name) {
  int fds[2] = {-1, -1};
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, fds) != 0)
    throw LinkError(fmt::format("cannot create a socket pair for {}: {}", name, std::strerror(errno)), errno);
  master_ = std::make_unique<SocketEnd>(fds[0], fmt::format("socketpair:{}", name));
  device_ = std::make_unique<SocketEnd>(fds[1], fmt::format("socketpair:{}:device", name));
}

}  // namespace cellctl::link

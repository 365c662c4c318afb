#include "web/client_watch.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <poll.h>
#include <sys/socket.h>

#include <charconv>
#include <cstring>
#include <filesystem>

namespace cellctl::web {
namespace {

// The address and port of a socket's end, as httplib writes them in a Request.
bool same_end(const sockaddr_storage& a, const std::string& address, int port) {
  char text[INET6_ADDRSTRLEN] = {};
  int p = 0;
  if (a.ss_family == AF_INET) {
    sockaddr_in v4{};
    std::memcpy(&v4, &a, sizeof v4);
    inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
    p = ntohs(v4.sin_port);
  } else if (a.ss_family == AF_INET6) {
    sockaddr_in6 v6{};
    std::memcpy(&v6, &a, sizeof v6);
    inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    p = ntohs(v6.sin6_port);
  } else {
    return false;
  }
  return p == port && address == text;
}

// The socket of the connection a request came on: the one whose two ends are the request's.
int socket_of(const httplib::Request& req) {
  if (req.ssl) return SSL_get_fd(req.ssl);
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    const auto name = entry.path().filename().string();
    int fd = -1;
    if (std::from_chars(name.data(), name.data() + name.size(), fd).ec != std::errc()) continue;
    sockaddr_storage peer{}, local{};
    socklen_t peer_size = sizeof peer, local_size = sizeof local;
    if (getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_size) != 0) continue;
    if (!same_end(peer, req.remote_addr, req.remote_port)) continue;
    if (getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_size) == 0 &&
        same_end(local, req.local_addr, req.local_port))
      return fd;
  }
  return -1;
}

}  // namespace

ClientWatch::ClientWatch(const httplib::Request& req) : fd_(socket_of(req)) {}

bool ClientWatch::gone() const {
  if (fd_ < 0) return true;
  pollfd p{fd_, POLLRDHUP, 0};
  return poll(&p, 1, 0) != 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR | POLLNVAL)) != 0;
}

}  // namespace cellctl::web

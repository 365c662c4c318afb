#include "web/page_server.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <httplib.h>
#include <poll.h>
#include <sys/socket.h>

#include <charconv>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "web/request_guard.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;

httplib::Headers security_headers() {
  return {
      {"Content-Security-Policy",
       "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; img-src 'self'; "
       "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"},
      {"X-Frame-Options", "DENY"},
      {"Cache-Control", "no-store"},
      {"X-Content-Type-Options", "nosniff"},
      {"Referrer-Policy", "no-referrer"},
  };
}

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

std::unique_ptr<httplib::Server> make_page_server(const PageOptions& options) {
  std::unique_ptr<httplib::Server> server;
  if (options.tls()) {
    auto tls = std::make_unique<httplib::SSLServer>(options.cert_file.c_str(), options.key_file.c_str());
    if (!tls->is_valid())
      throw std::runtime_error(fmt::format("the operator page's certificate {} or key {} cannot be used",
                                           options.cert_file.string(), options.key_file.string()));
    SSL_CTX_set_min_proto_version(tls->ssl_context(), TLS1_2_VERSION);
    server = std::move(tls);
  } else {
    server = std::make_unique<httplib::Server>();
  }
  const auto workers = options.max_streams + kCommandWorkers;
  server->new_task_queue = [workers] { return new httplib::ThreadPool(workers); };
  server->set_keep_alive_max_count(1);
  server->set_keep_alive_timeout(2);  // a connection that sends no request lets its worker go
  server->set_read_timeout(2s);
  server->set_write_timeout(3s);
  server->set_payload_max_length(kMaxBody);
  server->set_default_headers(security_headers());
  server->set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content(nlohmann::json{{"ok", false}, {"reason", "internal error"}}.dump(), "application/json");
  });
  return server;
}

bool client_gone(const httplib::Request& req) {
  const int fd = socket_of(req);
  if (fd < 0) return true;
  pollfd p{fd, POLLRDHUP, 0};
  return poll(&p, 1, 0) != 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR | POLLNVAL)) != 0;
}

}  // namespace cellctl::web

#include "web/request_guard.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <cctype>
#include <charconv>

#include "web/page_token.hpp"

namespace cellctl::web {
namespace {

using Clock = std::chrono::steady_clock;

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// The declared body length; nullopt when the header is not a number.
std::optional<std::uint64_t> content_length(const httplib::Request& req) {
  if (!req.has_header("Content-Length")) return 0;
  const auto text = req.get_header_value("Content-Length");
  std::uint64_t n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return n;
}

// The value of cookie `name` in the request's Cookie header, empty when absent.
std::string cookie(const httplib::Request& req, std::string_view name) {
  const auto header = req.get_header_value("Cookie");
  std::string_view rest = header;
  while (!rest.empty()) {
    const auto end = rest.find(';');
    auto pair = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    if (pair.size() > name.size() && pair.substr(0, name.size()) == name && pair[name.size()] == '=')
      return std::string(pair.substr(name.size() + 1));
  }
  return {};
}

bool public_path(const std::string& path) {
  return path == "/" || path == "/page.js" || path == "/page.css";
}

}  // namespace

RequestGuard::RequestGuard(const PageOptions& options)
    : token_(options.token),
      allowed_hosts_(options.allowed_hosts),
      tls_(options.tls()),
      public_metrics_(options.public_metrics),
      // A browser's cookie under HTTPS is __Host-: sent back only over HTTPS, to this host, for every path.
      cookie_name_(tls_ ? "__Host-cellctl_session" : "cellctl_session") {}

Verdict RequestGuard::admit(const httplib::Request& req) {
  if (auto why = foreign(req); !why.empty()) {
    ++forbidden_;
    return {403, std::move(why)};
  }
  const bool get = req.method == "GET" || req.method == "HEAD";
  if (!get && req.method != "POST") return {405, "only GET and POST"};
  const auto length = content_length(req);
  if (!length) return {400, "Content-Length is no number"};
  const bool chunked = req.has_header("Transfer-Encoding");
  if (get && (*length > 0 || chunked)) return {400, "a GET carries no body"};
  // httplib reads a POST's body without a length until the client closes: a worker held for nothing.
  if (!get && !chunked && !req.has_header("Content-Length")) return {411, "a POST needs Content-Length"};
  // Who asks, then how much: a caller without the token learns nothing else.
  if (auto refused = unknown_caller(req); refused.status != 0) return refused;
  if (*length > kMaxBody) {
    ++too_large_;
    return {413, fmt::format("a body may have at most {} bytes", kMaxBody)};
  }
  return {};
}

Verdict RequestGuard::unknown_caller(const httplib::Request& req) {
  if (public_path(req.path) || (public_metrics_ && req.path == "/metrics")) return {};
  const auto now = Clock::now();
  const auto credential = token_of(req);
  const bool login = req.path == "/login";
  if (credential != Credential::none || login) {
    if (const auto wait = backoff_.blocked(req.remote_addr, now); wait.count() > 0) {
      ++throttled_;
      return {429, "too many wrong tokens from this address: wait", static_cast<long>(wait.count())};
    }
  }
  if (login) return {};  // login() judges the token
  if (credential == Credential::wrong) return wrong_token(req.remote_addr);
  if (credential == Credential::right) {
    backoff_.succeeded(req.remote_addr);
    return {};
  }
  if (caller(req)) return {};
  ++unauthorised_;
  return {401, "log in with the page's token (or send it as X-Cellctl-Token or Authorization: Bearer)"};
}

std::optional<Caller> RequestGuard::caller(const httplib::Request& req) {
  if (token_of(req) == Credential::right) return Caller{"token", std::nullopt};
  const auto id = cookie(req, cookie_name_);
  if (id.empty()) return std::nullopt;
  const auto number = sessions_.find(id, Clock::now());
  if (!number) return std::nullopt;
  return Caller{fmt::format("session #{}", *number), number};
}

std::variant<SessionStore::Opened, Verdict> RequestGuard::login(const httplib::Request& req) {
  switch (token_of(req)) {
    case Credential::right:
      backoff_.succeeded(req.remote_addr);
      return sessions_.open(Clock::now());
    case Credential::wrong:
      return wrong_token(req.remote_addr);
    case Credential::none:
      break;
  }
  ++unauthorised_;
  return Verdict{401, "log in with the page's token in the X-Cellctl-Token header"};
}

void RequestGuard::logout(const httplib::Request& req) {
  if (const auto id = cookie(req, cookie_name_); !id.empty()) sessions_.close(id);
}

bool RequestGuard::session_open(std::uint64_t number) {
  return sessions_.open_now(number, Clock::now());
}

std::string RequestGuard::session_cookie(std::string_view id) const {
  return fmt::format("{}={}; Path=/; HttpOnly; SameSite=Strict{}{}", cookie_name_, id,
                     id.empty() ? "; Max-Age=0" : "", tls_ ? "; Secure" : "");
}

GuardCounters RequestGuard::counters() const {
  return {forbidden_.load(), unauthorised_.load(), wrong_tokens_.load(), throttled_.load(),
          too_large_.load()};
}

bool RequestGuard::names_this_page(std::string_view host_port, const httplib::Request& req) const {
  auto name = host_port;
  std::string_view port;
  if (!name.empty() && name.front() == '[') {  // [v6]:port
    const auto close = name.find(']');
    if (close == std::string_view::npos) return false;
    const auto rest = name.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') return false;
    if (!rest.empty()) port = rest.substr(1);
    name = name.substr(1, close - 1);
  } else if (const auto colon = name.rfind(':'); colon != std::string_view::npos) {
    port = name.substr(colon + 1);
    name = name.substr(0, colon);
  }
  int given = tls_ ? 443 : 80;
  if (!port.empty()) {
    const auto r = std::from_chars(port.data(), port.data() + port.size(), given);
    if (r.ec != std::errc() || r.ptr != port.data() + port.size()) return false;
  }
  if (given != req.local_port) return false;
  std::string_view reached = req.local_addr;
  if (reached.rfind("::ffff:", 0) == 0 && reached.find('.') != std::string_view::npos)
    reached.remove_prefix(7);  // IPv4 reached through an IPv6 socket
  if (same_name(name, reached) || (is_loopback(reached) && same_name(name, "localhost"))) return true;
  return std::any_of(allowed_hosts_.begin(), allowed_hosts_.end(),
                     [&](const std::string& h) { return same_name(name, h); });
}

std::string RequestGuard::foreign(const httplib::Request& req) const {
  if (!names_this_page(req.get_header_value("Host"), req))
    return "the Host header names no address or name of this page";
  if (req.has_header("Origin")) {
    const auto origin = req.get_header_value("Origin");
    const std::string_view scheme = tls_ ? "https://" : "http://";
    if (origin.rfind(scheme, 0) != 0 || !names_this_page(std::string_view(origin).substr(scheme.size()), req))
      return "the request comes from another site's page (Origin)";
  }
  return {};
}

RequestGuard::Credential RequestGuard::token_of(const httplib::Request& req) const {
  std::string given;
  if (req.has_header("X-Cellctl-Token")) {
    given = req.get_header_value("X-Cellctl-Token");
  } else {
    const auto auth = req.get_header_value("Authorization");
    if (auth.rfind("Bearer ", 0) != 0) return Credential::none;
    given = auth.substr(7);
  }
  return same_secret(given, token_) ? Credential::right : Credential::wrong;
}

Verdict RequestGuard::wrong_token(const std::string& address) {
  ++wrong_tokens_;
  ++unauthorised_;
  backoff_.failed(address, Clock::now());
  return {401, "a valid token is required"};
}

}  // namespace cellctl::web

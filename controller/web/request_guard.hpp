#pragma once
// Every request to the operator page passes here first, on its request line and headers alone —
// before its body is read (httplib's pre-routing handler, and its 100-continue handler) — so bad
// input is refused before it costs anything:
//  - Host must name this page: the address the client reached it at, localhost on loopback, or a
//    name given by --http-allow-host, with the page's port; Origin, when a browser sends one, the
//    same with the page's scheme. Else 403: a DNS name rebound to the controller, another site's
//    page posting here.
//  - Only GET (no body) and POST (with Content-Length, or chunked).
//  - Everything but the page itself (/, its script and style) and /login needs the caller known: by
//    the token (X-Cellctl-Token, or Authorization: Bearer as Prometheus sends it) or by a session
//    cookie (session_store.hpp). Else 401. /metrics may be public (--http-public-metrics).
//  - Wrong tokens back off per address (failure_backoff.hpp): 429 at once while it waits.
//  - Then, for a known caller, a body over kMaxBody is refused 413, unread.
// Thread-safe.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "schema/command_payload.hpp"
#include "web/failure_backoff.hpp"
#include "web/page_options.hpp"
#include "web/session_store.hpp"

namespace httplib {
struct Request;
}

namespace cellctl::web {

// A command's body, and every other: the JSON limit of the command path.
inline constexpr std::size_t kMaxBody = schema::kMaxCommandBytes;

// A refusal (status 0: none; go on).
struct Verdict {
  int status = 0;
  std::string reason;
  long retry_after_s = 0;  // 429: when to try again
};

// Who a request comes from: "token" or "session #n" (never the secret itself).
struct Caller {
  std::string who;
  std::optional<std::uint64_t> session;
};

struct GuardCounters {
  std::uint64_t forbidden = 0;     // 403: Host or Origin
  std::uint64_t unauthorised = 0;  // 401: no token, no session, or a wrong token
  std::uint64_t wrong_tokens = 0;
  std::uint64_t throttled = 0;  // 429
  std::uint64_t too_large = 0;  // 413
};

class RequestGuard {
 public:
  explicit RequestGuard(const PageOptions& options);

  // The checks above.
  [[nodiscard]] Verdict admit(const httplib::Request& req);
  // Who an admitted request is; nullopt for a public path's anonymous caller (or a session that has
  // just ended).
  [[nodiscard]] std::optional<Caller> caller(const httplib::Request& req);
  // POST /login: a new session for the right token; a wrong one counts as in admit().
  [[nodiscard]] std::variant<SessionStore::Opened, Verdict> login(const httplib::Request& req);
  // POST /logout: the request's session ends.
  void logout(const httplib::Request& req);
  [[nodiscard]] bool session_open(std::uint64_t number);
  // The Set-Cookie value for a session (an empty id: the cookie deleted).
  [[nodiscard]] std::string session_cookie(std::string_view id) const;
  [[nodiscard]] GuardCounters counters() const;

 private:
  enum class Credential { none, right, wrong };
  [[nodiscard]] bool names_this_page(std::string_view host_port, const httplib::Request& req) const;
  [[nodiscard]] std::string foreign(const httplib::Request& req) const;
  // 401 or 429 unless the path is public or the caller known (or, for /login, not held back).
  [[nodiscard]] Verdict unknown_caller(const httplib::Request& req);
  [[nodiscard]] Credential token_of(const httplib::Request& req) const;
  [[nodiscard]] Verdict wrong_token(const std::string& address);

  const std::string token_;
  const std::vector<std::string> allowed_hosts_;
  const bool tls_;
  const bool public_metrics_;
  const std::string cookie_name_;
  SessionStore sessions_;
  FailureBackoff backoff_;
  std::atomic<std::uint64_t> forbidden_{0}, unauthorised_{0}, wrong_tokens_{0}, throttled_{0}, too_large_{0};
};

}  // namespace cellctl::web

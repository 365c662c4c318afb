#pragma once
// The page's sessions. A browser's EventSource cannot send the token in a header, and the token must
// never sit in the page: so a browser logs in once (POST /login, the token in a header) and is known
// after that by a session cookie (HttpOnly, SameSite=Strict). A session id is 128 random bits, kept
// only here and in that cookie, and compared in constant time. A session ends when logged out, after
// its lifetime, or when more than `capacity` are open (the oldest goes). Thread-safe.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cellctl::web {

class SessionStore {
 public:
  using Clock = std::chrono::steady_clock;
  struct Opened {
    std::string id;          // the cookie's value
    std::uint64_t number{};  // "session #n" in the journal: never the id
  };

  explicit SessionStore(std::chrono::seconds lifetime = std::chrono::hours(12), std::size_t capacity = 64);

  [[nodiscard]] Opened open(Clock::time_point now);
  // The session's number, nullopt for an unknown or expired id.
  [[nodiscard]] std::optional<std::uint64_t> find(std::string_view id, Clock::time_point now);
  // Whether session `number` is still open (a live-event stream ends with its session).
  [[nodiscard]] bool open_now(std::uint64_t number, Clock::time_point now);
  void close(std::string_view id);

 private:
  struct Session {
    std::string id;
    std::uint64_t number{};
    Clock::time_point expires;
  };
  void drop_expired(Clock::time_point now);  // under mutex_

  const std::chrono::seconds lifetime_;
  const std::size_t capacity_;
  std::mutex mutex_;
  std::vector<Session> sessions_;  // oldest first
  std::uint64_t next_number_ = 1;
};

}  // namespace cellctl::web

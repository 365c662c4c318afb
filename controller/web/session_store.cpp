#include "web/session_store.hpp"

#include <algorithm>

#include "web/page_token.hpp"

namespace cellctl::web {

SessionStore::SessionStore(std::chrono::seconds lifetime, std::size_t capacity)
    : lifetime_(lifetime), capacity_(capacity) {}

SessionStore::Opened SessionStore::open(Clock::time_point now) {
  Opened o{random_hex(16), 0};
  const std::lock_guard lock(mutex_);
  drop_expired(now);
  if (sessions_.size() >= capacity_) sessions_.erase(sessions_.begin());
  o.number = next_number_++;
  sessions_.push_back({o.id, o.number, now + lifetime_});
  return o;
}

std::optional<std::uint64_t> SessionStore::find(std::string_view id, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  drop_expired(now);
  // Every id compared in full, so the time taken says nothing of how close a guess came.
  std::optional<std::uint64_t> found;
  for (const auto& s : sessions_)
    if (same_secret(id, s.id)) found = s.number;
  return found;
}

bool SessionStore::open_now(std::uint64_t number, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  drop_expired(now);
  return std::any_of(sessions_.begin(), sessions_.end(),
                     [&](const Session& s) { return s.number == number; });
}

void SessionStore::close(std::string_view id) {
  const std::lock_guard lock(mutex_);
  std::erase_if(sessions_, [&](const Session& s) { return same_secret(id, s.id); });
}

void SessionStore::drop_expired(Clock::time_point now) {
  std::erase_if(sessions_, [&](const Session& s) { return s.expires <= now; });
}

}  // namespace cellctl::web

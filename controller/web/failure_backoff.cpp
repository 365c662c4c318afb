#include "web/failure_backoff.hpp"

#include <algorithm>

namespace cellctl::web {

std::chrono::seconds FailureBackoff::blocked(const std::string& address, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  const auto it = records_.find(address);
  if (it == records_.end() || it->second.until <= now) return std::chrono::seconds(0);
  // Rounded up: a client told 0 s would come straight back into the window.
  return std::chrono::ceil<std::chrono::seconds>(it->second.until - now);
}

void FailureBackoff::failed(const std::string& address, Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  if (records_.size() >= kAddresses && !records_.contains(address)) {
    const auto quietest =
        std::min_element(records_.begin(), records_.end(),
                         [](const auto& a, const auto& b) { return a.second.last < b.second.last; });
    records_.erase(quietest);
  }
  auto& r = records_[address];
  ++r.failures;
  r.last = now;
  if (r.failures >= kFreeFailures)
    r.until = now + std::chrono::seconds(1u << std::min(r.failures - kFreeFailures, 8u));
}

void FailureBackoff::succeeded(const std::string& address) {
  const std::lock_guard lock(mutex_);
  records_.erase(address);
}

}  // namespace cellctl::web

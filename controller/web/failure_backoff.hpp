#pragma once
// Wrong tokens, counted per client address. After kFreeFailures, a request that brings a token from
// that address is answered 429 at once for a window that doubles with each further failure (1 s,
// 2 s, … 256 s): guessing costs the guesser time and the page no worker, as nothing waits. A right
// token clears the address. A browser known by its session cookie is never held back, so a guesser
// behind the same address cannot keep the operator's page from stopping the cell.
// Thread-safe; bounded (when kAddresses are known, the one quiet the longest is forgotten).

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <unordered_map>

namespace cellctl::web {

class FailureBackoff {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr unsigned kFreeFailures = 5;
  static constexpr std::size_t kAddresses = 4096;

  // How long the address must still wait; zero when it may try.
  [[nodiscard]] std::chrono::seconds blocked(const std::string& address, Clock::time_point now);
  void failed(const std::string& address, Clock::time_point now);
  void succeeded(const std::string& address);

 private:
  struct Record {
    unsigned failures = 0;
    Clock::time_point until{};
    Clock::time_point last{};
  };
  std::mutex mutex_;
  std::unordered_map<std::string, Record> records_;
};

}  // namespace cellctl::web

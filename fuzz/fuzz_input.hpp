#pragma once
// What every fuzz target shares: a cursor over the fuzzer's bytes that hands out parameters (a
// shape, a chunk size) and the bytes to decode, and FUZZ_CHECK, which aborts with the broken
// property so that libFuzzer records the input as a finding and the replay test fails on it.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

namespace cellctl::fuzz {

class FuzzInput {
 public:
  explicit FuzzInput(std::span<const std::uint8_t> bytes) noexcept : rest_(bytes) {}

  // The next byte as a parameter; 0 when the input is used up.
  [[nodiscard]] std::uint8_t byte() noexcept {
    if (rest_.empty()) return 0;
    const std::uint8_t b = rest_.front();
    rest_ = rest_.subspan(1);
    return b;
  }
  // Up to `n` bytes to feed (fewer at the end of the input).
  [[nodiscard]] std::span<const std::uint8_t> take(std::size_t n) noexcept {
    const auto piece = rest_.first(n < rest_.size() ? n : rest_.size());
    rest_ = rest_.subspan(piece.size());
    return piece;
  }
  [[nodiscard]] std::span<const std::uint8_t> rest() const noexcept { return rest_; }
  [[nodiscard]] bool empty() const noexcept { return rest_.empty(); }

 private:
  std::span<const std::uint8_t> rest_;
};

[[noreturn]] inline void property_broken(const char* what, const char* file, int line) noexcept {
  std::fprintf(stderr, "%s:%d: fuzz property broken: %s\n", file, line, what);
  std::abort();
}

// A property an open issue still breaks: fatal like any other, unless the run tolerates open
// findings (CELLCTL_FUZZ_TOLERATE_OPEN set, as fuzz/run_all.sh does, so that one known defect does
// not end the exploration of everything else) — then it is reported once per place and the input
// is not checked further.
inline void open_property_broken(const char* what, const char* owner, const char* file, int line,
                                 bool& reported) noexcept {
  static const bool tolerate = std::getenv("CELLCTL_FUZZ_TOLERATE_OPEN") != nullptr;
  if (!tolerate) property_broken(what, file, line);
  if (reported) return;
  reported = true;
  std::fprintf(stderr, "%s:%d: open finding (%s), tolerated: %s\n", file, line, owner, what);
}

}  // namespace cellctl::fuzz

// A property every input must keep (not an assert: it stays on in release builds).
#define FUZZ_CHECK(condition) \
  ((condition) ? void(0) : ::cellctl::fuzz::property_broken(#condition, __FILE__, __LINE__))

// The same for a property an open issue breaks (`owner` says where it is being fixed); ends the
// target's function when tolerated.
#define FUZZ_CHECK_OPEN(condition, owner)                                                      \
  do {                                                                                         \
    if (!(condition)) {                                                                        \
      static bool reported_ = false;                                                           \
      ::cellctl::fuzz::open_property_broken(#condition, owner, __FILE__, __LINE__, reported_); \
      return;                                                                                  \
    }                                                                                          \
  } while (false)

// A decoder that never runs dry of events is a hang: bounded by this many events per fed chunk.
namespace cellctl::fuzz {
inline constexpr int kMaxEventsPerChunk = 4096;
}

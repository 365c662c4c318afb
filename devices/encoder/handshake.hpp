#pragma once
// The master's side of the encoder's edge-based handshakes (manual 4.3.2–4.3.5, 4.4.1, 4.4.2), one
// at a time, stepped once per completed Data_Exchange with the input that answered output():
//   preset (bit 31)          1: out bit 31 + value      → in bit 31 set, new position
//                            2: out 0                   → in bit 31 clear
//   (without status bits the slave has no acknowledge bit: each phase lasts one exchange)
//   direction (bit 28)       1: out bit 28 + bit 0 = wanted sequence → in bit 28 = wanted, bit 0 echo
//                            2: out 0                   → in bit 28 = wanted (new position)
//   Teach-In start (bit 30)  1: out bit 30              → in bit 30 set
//                            2: out 0                   → in bit 30 still set (Teach-In running)
//   Teach-In end (bit 29)    1: out bit 29 + distance   → in bits 29+30 set, bits 0–24 total resolution
//                            2: out 0                   → in bits 29, 30 clear (scaled position)
// A phase that is not acknowledged within kMaxExchanges exchanges fails with a reason.

#include <cstdint>
#include <string_view>

#include "encoder/cyclic.hpp"
#include "encoder/parameters.hpp"

namespace cellctl::encoder {

class Handshake {
 public:
  enum class Kind : std::uint8_t { none, preset, direction, teach_in_start, teach_in_end };
  enum class Phase : std::uint8_t { idle, request, release, done, failed };
  static constexpr std::uint32_t kMaxExchanges = 50;

  // Each returns false (and changes nothing) while another handshake runs or for a value the bits
  // cannot carry; `with_status` says whether the input carries the 7 status bits.
  [[nodiscard]] bool start_preset(std::uint32_t value, bool with_status) noexcept;
  [[nodiscard]] bool start_direction(CodeSequence wanted) noexcept;
  [[nodiscard]] bool start_teach_in() noexcept;
  [[nodiscard]] bool end_teach_in(std::uint32_t distance) noexcept;

  // The output word to send now (0 when idle, as 4.3 recommends).
  [[nodiscard]] std::uint32_t output() const noexcept;
  // One exchange completed with `in` as the answer to output().
  void on_input(const CyclicInput& in) noexcept;
  // Forget a finished (done/failed) handshake so that the next may start; also aborts on bus loss.
  void reset() noexcept { *this = Handshake{}; }
  // A running handshake fails now (data exchange lost): the outcome on the encoder is unknown.
  void abort(std::string_view why) noexcept {
    if (busy()) {
      phase_ = Phase::failed;
      failure_ = why;
    }
  }

  [[nodiscard]] Kind kind() const noexcept { return kind_; }
  [[nodiscard]] Phase phase() const noexcept { return phase_; }
  [[nodiscard]] bool busy() const noexcept { return phase_ == Phase::request || phase_ == Phase::release; }
  // Preset/direction: the position the slave reported; Teach-In end: the total resolution.
  [[nodiscard]] std::uint32_t result() const noexcept { return result_; }
  [[nodiscard]] std::string_view failure() const noexcept { return failure_; }

 private:
  bool begin(Kind k, std::uint32_t request_word) noexcept;
  void advance(bool acknowledged, std::string_view what) noexcept;

  Kind kind_ = Kind::none;
  Phase phase_ = Phase::idle;
  std::uint32_t request_word_ = 0;
  bool with_status_ = true;
  CodeSequence wanted_ = CodeSequence::cw;
  std::uint32_t exchanges_ = 0;
  std::uint32_t result_ = 0;
  std::string_view failure_;
};

[[nodiscard]] std::string_view to_string(Handshake::Kind k) noexcept;

}  // namespace cellctl::encoder

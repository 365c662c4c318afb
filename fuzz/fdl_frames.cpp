// The FDL frame decoder fed arbitrary octets in arbitrary pieces. Properties: every event consumes
// octets (no endless loop, never stuck full); a frame it accepts encodes back and parses to the same
// frame; and when the re-encoding uses the same frame type, it is exactly as long as the octets
// the decoder consumed — nothing was cut off or invented.

#include <array>

#include "fuzz_input.hpp"
#include "profibus/fdl_decoder.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {
namespace {

void check_round_trip(const profibus::FdlFrame& frame, std::size_t consumed) {
  std::array<std::uint8_t, profibus::kMaxFrameSize> out{};
  const std::size_t n = profibus::encode(frame, out);
  FUZZ_CHECK(n > 0);
  FUZZ_CHECK(n == profibus::encoded_size(frame));
  const auto again = profibus::parse_frame(std::span(out).first(n));
  FUZZ_CHECK(again.status == profibus::FdlParse::Status::frame);
  FUZZ_CHECK(again.consumed == n);
  auto same_kind = again.frame;
  same_kind.kind = frame.kind;
  FUZZ_CHECK(same_kind == frame);
  // Found: SD2 with LE = 249 and no SAPs, 246 data octets cut to 244 (findings/fdl_frames).
  if (again.frame.kind == frame.kind) FUZZ_CHECK(n == consumed);
}

}  // namespace

void fdl_frames(std::span<const std::uint8_t> bytes) {
  FuzzInput in(bytes);
  const std::size_t piece = 1u + in.byte();  // the octets arrive in pieces of 1..256
  profibus::FdlDecoder decoder;
  while (!in.empty()) {
    auto chunk = in.take(piece);
    while (!chunk.empty()) {
      const std::size_t taken = decoder.push(chunk);
      chunk = chunk.subspan(taken);
      bool progress = taken > 0;
      int events = 0;
      for (;;) {
        const std::size_t before = decoder.buffered();
        const auto e = decoder.next();
        if (!e) break;
        FUZZ_CHECK(++events < kMaxEventsPerChunk);
        const std::size_t consumed = before - decoder.buffered();
        FUZZ_CHECK(consumed > 0);
        progress = true;
        if (e->error == profibus::FdlError::none) check_round_trip(e->frame, consumed);
      }
      FUZZ_CHECK(progress);  // a full buffer that waits for more would never end
    }
  }
}

}  // namespace cellctl::fuzz

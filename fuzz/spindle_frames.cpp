// The spindle converter's frame decoder (both directions share the framing and the codec) fed
// arbitrary bytes. Properties: every message it decodes encodes to a frame that decodes to the
// same message, and the one-frame decoder (Codec::decode_frame) agrees with the stream decoder.

#include <array>

#include "fuzz_input.hpp"
#include "spindle/codec.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {
namespace {

void check_round_trip(const spindle::Message& message) {
  std::array<std::uint8_t, spindle::kMaxFrameLength> frame{};
  const std::size_t n = spindle::Codec::encode(message, frame);
  FUZZ_CHECK(n > 0);
  const auto again = spindle::Codec::decode_frame(std::span(frame).first(n));
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(again.message == message);
}

}  // namespace

void spindle_frames(std::span<const std::uint8_t> bytes) {
  spindle::FrameDecoder decoder;
  std::size_t frames = 0;
  for (const std::uint8_t b : bytes) {
    const auto out = decoder.push(b);
    if (!out) continue;
    ++frames;
    if (out->ok()) check_round_trip(out->message);
  }
  FUZZ_CHECK(decoder.skipped_bytes() <= bytes.size());

  // The whole input as one frame: where decode_frame accepts it, the stream decoder does too.
  const auto whole = spindle::Codec::decode_frame(bytes);
  if (whole.ok()) {
    check_round_trip(whole.message);
    spindle::FrameDecoder fresh;
    std::optional<spindle::Decoded> last;
    for (const std::uint8_t b : bytes)
      if (auto out = fresh.push(b)) last = out;
    FUZZ_CHECK(last && last->ok() && last->message == whole.message);
  }
  (void)frames;
}

}  // namespace cellctl::fuzz

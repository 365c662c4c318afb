// The SCU's two stream decoders fed arbitrary bytes in arbitrary pieces. Properties: every byte fed
// is accounted for (dropped by an error, part of a decoded telegram, or still buffered); an error
// always drops something (no endless error loop); the stream never sits full waiting for more; and
// every telegram it hands out encodes back to a telegram of the same length that decodes the same.

#include <array>
#include <chrono>

#include "fuzz_input.hpp"
#include "scu/reply_stream.hpp"
#include "scu/request_stream.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {
namespace {

constexpr std::array<scu::Command, 7> kCommands = {
    scu::Command::get,  scu::Command::transfer, scu::Command::cyclic, scu::Command::execute,
    scu::Command::stop, scu::Command::open,     scu::Command::abort};

// The first byte after the shape: the size of the pieces the bytes arrive in, 1..64, so that both
// byte-by-byte arrival and whole bursts are explored.
std::size_t chunk_size(FuzzInput& in) noexcept {
  return 1u + in.byte() % 64u;
}

// Encodes `reply`, decodes it again, encodes that: the two encodings are the same telegram.
std::size_t check_reply_round_trip(const scu::Reply& reply, scu::ReplyShape shape) {
  scu::ReplyBytes first;
  FUZZ_CHECK(scu::encode_reply(reply, first));
  const auto again = scu::decode_reply(first.view(), shape);
  FUZZ_CHECK(again.ok());
  scu::ReplyBytes second;
  FUZZ_CHECK(scu::encode_reply(again.value, second));
  FUZZ_CHECK(first == second);
  return first.size();
}

std::size_t check_request_round_trip(const scu::Request& request) {
  scu::RequestBytes first;
  FUZZ_CHECK(scu::encode_request(request, first));
  const auto again = scu::decode_request(first.view());
  FUZZ_CHECK(again.ok());
  scu::RequestBytes second;
  FUZZ_CHECK(scu::encode_request(again.value, second));
  FUZZ_CHECK(first == second);
  FUZZ_CHECK(scu::request_frame_length(first.view()).length == first.size());
  return first.size();
}

// Bytes fed into a stream, and bytes it accounted for: dropped by errors or part of telegrams.
struct Ledger {
  std::size_t fed = 0;
  std::size_t accounted = 0;
};

// Feeds one piece into `stream` (through `feed`, which returns how many bytes it took) and drains
// its events after every feed. Properties both streams share: an error drops something, events run
// dry, and a stream never sits full waiting for more. `decoded` checks a decoded telegram and
// returns its length.
template <class Stream, class Feed, class Decoded>
void feed_piece(Stream& stream, std::span<const std::uint8_t> chunk, Ledger& ledger, Feed&& feed,
                Decoded&& decoded) {
  using Kind = typename Stream::Event::Kind;
  while (!chunk.empty()) {
    const std::size_t taken = feed(chunk);
    chunk = chunk.subspan(taken);
    ledger.fed += taken;
    bool progress = taken > 0;
    for (int events = 1;; ++events) {
      FUZZ_CHECK(events < kMaxEventsPerChunk);
      const auto e = stream.next();
      if (e.kind == Kind::need_more) break;
      progress = true;
      if (e.kind == Kind::error) {
        FUZZ_CHECK(e.dropped > 0);
        ledger.accounted += e.dropped;
        continue;
      }
      ledger.accounted += decoded(e);
    }
    FUZZ_CHECK(progress);
  }
}

}  // namespace

void scu_reply_stream(std::span<const std::uint8_t> bytes) {
  FuzzInput in(bytes);
  const std::uint8_t shape_byte = in.byte();
  const scu::ReplyShape shape{kCommands[shape_byte % kCommands.size()], (shape_byte & 0x80u) != 0};
  const std::size_t piece = chunk_size(in);
  scu::ReplyStream stream;
  stream.expect(shape);
  Ledger ledger;
  while (!in.empty())
    feed_piece(
        stream, in.take(piece), ledger,
        [&](std::span<const std::uint8_t> chunk) { return stream.feed(chunk); },
        [&](const scu::ReplyStream::Event& e) {
          FUZZ_CHECK(e.reply.command == shape.command);
          return check_reply_round_trip(e.reply, shape);
        });
  FUZZ_CHECK(ledger.accounted + stream.buffered() == ledger.fed);
}

void scu_request_stream(std::span<const std::uint8_t> bytes) {
  FuzzInput in(bytes);
  const std::size_t piece = chunk_size(in);
  // 0..2.55 s between pieces: across the 1 s inter-byte time-out and well inside it.
  const auto gap = std::chrono::milliseconds(10 * in.byte());
  scu::RequestStream stream;
  link::TimePoint now{std::chrono::seconds(1)};
  Ledger ledger;
  while (!in.empty()) {
    now += gap;
    feed_piece(
        stream, in.take(piece), ledger,
        [&](std::span<const std::uint8_t> chunk) {
          const std::size_t buffered_before = stream.buffered();
          const std::size_t expired = stream.expire(now);
          FUZZ_CHECK(expired == 0 || expired == buffered_before);
          ledger.accounted += expired;
          return stream.feed(chunk, now);
        },
        [&](const scu::RequestStream::Event& e) {
          FUZZ_CHECK(static_cast<std::uint8_t>(scu::command_of(e.request)) == e.command_byte);
          return check_request_round_trip(e.request);
        });
  }
  FUZZ_CHECK(ledger.accounted + stream.buffered() == ledger.fed);
}

}  // namespace cellctl::fuzz

// The stream decoders: replies and requests arriving byte by byte, after garbage, damaged, or cut off.

#include <gtest/gtest.h>

#include <vector>

#include "scu/reply_stream.hpp"
#include "scu/request_stream.hpp"
#include "wire/hex.hpp"

namespace cellctl::scu {
namespace {

using Kind = ReplyStream::Event::Kind;
using std::chrono::milliseconds;

std::vector<std::uint8_t> reply_bytes(const char* text) {
  return *wire::parse_hex(text);
}

TEST(ScuReplyStream, FramesAReplyFedOneByteAtATime) {
  ReplyStream s;
  s.expect({Command::get, true});
  const auto bytes = reply_bytes("52 47 06 04 00 b0 01 00 00 ed 9a");
  for (std::size_t i = 0; i + 1 < bytes.size(); ++i) {
    ASSERT_EQ(s.feed(std::span(bytes).subspan(i, 1)), 1u);
    EXPECT_EQ(s.next().kind, Kind::need_more) << "after byte " << i;
  }
  ASSERT_EQ(s.feed(std::span(bytes).last(1)), 1u);
  const auto e = s.next();
  ASSERT_EQ(e.kind, Kind::reply);
  EXPECT_EQ(wire::to_hex(e.reply.data), "b0 01 00 00");
  EXPECT_EQ(s.next().kind, Kind::need_more);
}

TEST(ScuReplyStream, ResynchronisesAfterGarbage) {
  ReplyStream s;
  s.expect({Command::get, true});
  // Noise, a stray 'R' that starts nothing valid, then the real reply.
  (void)s.feed(reply_bytes("00 ff 13 52 00 52 47 06 01 00 31 b3 bb"));
  auto e = s.next();
  EXPECT_EQ(e.kind, Kind::error);
  EXPECT_EQ(e.error, DecodeError::bad_start);
  EXPECT_EQ(e.dropped, 3u);
  e = s.next();
  EXPECT_EQ(e.kind, Kind::error);
  EXPECT_EQ(e.error, DecodeError::unknown_command);
  e = s.next();
  EXPECT_EQ(e.error, DecodeError::bad_start) << "the 00 after the stray 'R'";
  EXPECT_EQ(e.dropped, 1u);
  e = s.next();
  ASSERT_EQ(e.kind, Kind::reply);
  EXPECT_EQ(wire::to_hex(e.reply.data), "31");
}

TEST(ScuReplyStream, ReportsBadCrcAndDropsTheWholeDamagedReply) {
  ReplyStream s;
  s.expect({Command::cyclic, false});
  (void)s.feed(reply_bytes("52 43 06 f7 09"));
  const auto e = s.next();
  EXPECT_EQ(e.kind, Kind::error);
  EXPECT_EQ(e.error, DecodeError::bad_crc);
  EXPECT_EQ(e.dropped, 5u);
  EXPECT_EQ(s.buffered(), 0u);
}

TEST(ScuReplyStream, ReportsAReplyToAnotherCommandAndAnImpossibleLength) {
  ReplyStream s;
  s.expect({Command::get, true});
  (void)s.feed(reply_bytes("52 54 06 13 92"));
  EXPECT_EQ(s.next().error, DecodeError::unexpected_command);
  s.expect({Command::get, true});
  (void)s.feed(reply_bytes("52 47 06 ff 7f"));
  EXPECT_EQ(s.next().error, DecodeError::bad_length);
}

TEST(ScuReplyStream, ErrorReplyNeedsNoCtpAndNothingIsExpectedWhenIdle) {
  ReplyStream s;
  s.expect({Command::get, true});
  (void)s.feed(reply_bytes("52 47 80 7d 35"));
  const auto e = s.next();
  ASSERT_EQ(e.kind, Kind::reply);
  EXPECT_EQ(e.reply.status, Status::checksum_error);
  s.expect_nothing();
  (void)s.feed(reply_bytes("52 47 80 7d 35"));
  EXPECT_EQ(s.next().error, DecodeError::bad_start) << "a reply nobody asked for is garbage";
}

TEST(ScuRequestStream, FramesBackToBackRequests) {
  RequestStream s;
  const link::TimePoint t{};
  (void)s.feed(reply_bytes("52 4f 00 5c 2d 52 43 01 00 ff 31 8d 52 54 06 00 21 30 39 30 00 00 78 4e"), t);
  auto e = s.next();
  ASSERT_EQ(e.kind, RequestStream::Event::Kind::request);
  EXPECT_TRUE(std::holds_alternative<OpenRequest>(e.request));
  e = s.next();
  ASSERT_EQ(e.kind, RequestStream::Event::Kind::request);
  EXPECT_TRUE(std::holds_alternative<CyclicRequest>(e.request));
  e = s.next();
  ASSERT_EQ(e.kind, RequestStream::Event::Kind::request);
  EXPECT_EQ(std::get<TransferRequest>(e.request).data_id, 0x3021);
  EXPECT_EQ(s.next().kind, RequestStream::Event::Kind::need_more);
}

TEST(ScuRequestStream, DiscardsAPartialRequestAfterTheInterByteTimeout) {
  RequestStream s;
  link::TimePoint t{};
  const auto ro = reply_bytes("52 4f 00 5c 2d");
  (void)s.feed(std::span(ro).first(3), t);
  EXPECT_EQ(s.expire(t + milliseconds(1000)), 0u) << "1000 ms is still within the limit";
  EXPECT_EQ(s.expire(t + milliseconds(1001)), 3u);
  // The rest arriving late is garbage now, and a fresh RO after it is framed normally.
  t += milliseconds(1500);
  (void)s.feed(std::span(ro).last(2), t);
  (void)s.feed(ro, t);
  auto e = s.next();
  EXPECT_EQ(e.kind, RequestStream::Event::Kind::error);
  EXPECT_EQ(e.error, DecodeError::bad_start);
  e = s.next();
  ASSERT_EQ(e.kind, RequestStream::Event::Kind::request);
  EXPECT_TRUE(std::holds_alternative<OpenRequest>(e.request));
}

TEST(ScuRequestStream, NamesTheCommandOfABrokenRequest) {
  RequestStream s;
  (void)s.feed(reply_bytes("52 47 11 00 2c 31"), {});
  auto e = s.next();
  EXPECT_EQ(e.error, DecodeError::bad_crc);
  EXPECT_EQ(e.command_byte, 'G');
  (void)s.feed(reply_bytes("52 5a 01 02"), {});
  e = s.next();
  EXPECT_EQ(e.error, DecodeError::unknown_command);
  EXPECT_EQ(e.command_byte, 'Z');
  EXPECT_EQ(s.buffered(), 0u);
}

}  // namespace
}  // namespace cellctl::scu

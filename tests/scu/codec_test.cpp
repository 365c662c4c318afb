// The SCU codec byte-exact against every SCU vector of protocol-notes.md, round trips of every request
// and reply, and what bad bytes turn into.

#include "scu/codec.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "scu/crc16.hpp"
#include "wire/hex.hpp"

namespace cellctl::scu {
namespace {

std::vector<std::uint8_t> hex(const char* text) {
  return *wire::parse_hex(text);
}

std::string encoded(const Request& r) {
  RequestBytes out;
  EXPECT_TRUE(encode_request(r, out));
  return wire::to_hex(out.view());
}

std::string encoded(const Reply& r) {
  ReplyBytes out;
  EXPECT_TRUE(encode_reply(r, out));
  return wire::to_hex(out.view());
}

TEST(ScuCrc16, MatchesTheManualsTableAndChecksToZeroWithSwappedCrc) {
  const auto frame = hex("52 4f 00 5c 2d");
  EXPECT_EQ(crc16(std::span(frame).first(3)), 0x2d5c);
  // The manual's check: CRC over the frame with the CRC bytes swapped back (high, low) is 0.
  const auto swapped = hex("52 4f 00 2d 5c");
  EXPECT_EQ(crc16(swapped), 0);
  // Single bytes reproduce table entries: crc16({b}) == CRC_TABLE[b].
  const std::uint8_t b1[] = {0x01}, b80[] = {0x80}, bff[] = {0xFF};
  EXPECT_EQ(crc16(b1), 0x1021);
  EXPECT_EQ(crc16(b80), 0x9188);
  EXPECT_EQ(crc16(bff), 0x1EF0);
}

TEST(ScuCodec, RequestsMatchTheNotesVectors) {
  EXPECT_EQ(encoded(OpenRequest{0}), "52 4f 00 5c 2d");
  EXPECT_EQ(encoded(CyclicRequest{}), "52 43 01 00 ff 31 8d");
  const std::uint8_t speed100[] = {0x64, 0x00};
  EXPECT_EQ(encoded(TransferRequest{0x3011, speed100}), "52 54 04 00 11 30 64 00 6a 06");
  const std::uint8_t pos12345[] = {0x39, 0x30, 0x00, 0x00};
  EXPECT_EQ(encoded(TransferRequest{0x3021, pos12345}), "52 54 06 00 21 30 39 30 00 00 78 4e");
  const std::uint8_t pos_minus200[] = {0x38, 0xff, 0xff, 0xff};
  EXPECT_EQ(encoded(TransferRequest{0x3022, pos_minus200}), "52 54 06 00 22 30 38 ff ff ff e5 e1");
  EXPECT_EQ(encoded(ExecuteRequest{0, 9, 0xFF}), "52 45 00 09 ff 00 27");
  EXPECT_EQ(encoded(StopRequest{0, 0xFF}), "52 53 00 ff 3d 81");
  EXPECT_EQ(encoded(GetRequest{0x0011}), "52 47 11 00 2c 30");
  EXPECT_EQ(encoded(GetRequest{0x0171}), "52 47 71 01 27 2b");
  EXPECT_EQ(encoded(AbortRequest{}), "52 41 38 30");
}

TEST(ScuCodec, RepliesMatchTheNotesVectors) {
  EXPECT_EQ(encoded(Reply{Command::cyclic, Status::ack, false, {}}), "52 43 06 f7 08");
  EXPECT_EQ(encoded(Reply{Command::transfer, Status::ack, false, {}}), "52 54 06 13 92");
  const std::uint8_t pos432[] = {0xb0, 0x01, 0x00, 0x00};
  EXPECT_EQ(encoded(Reply{Command::get, Status::ack, true, pos432}), "52 47 06 04 00 b0 01 00 00 ed 9a");
  const std::uint8_t status31[] = {0x31};
  EXPECT_EQ(encoded(Reply{Command::get, Status::ack, true, status31}), "52 47 06 01 00 31 b3 bb");
  EXPECT_EQ(encoded(Reply{Command::get, Status::checksum_error, true, {}}), "52 47 80 7d 35");
  EXPECT_EQ(encoded(Reply{Command::execute, Status::permission_error, false, {}}), "52 45 84 9b 13");
}

TEST(ScuCodec, DecodesTheNotesReplyVectors) {
  const auto rg = hex("52 47 06 04 00 b0 01 00 00 ed 9a");
  const auto d = decode_reply(rg, {Command::get, true});
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d.value.status, Status::ack);
  EXPECT_EQ(wire::to_hex(d.value.data), "b0 01 00 00");

  const auto cse = hex("52 47 80 7d 35");
  const auto e = decode_reply(cse, {Command::get, true});
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e.value.status, Status::checksum_error);
  EXPECT_TRUE(e.value.data.empty()) << "an error reply has no ctp even where the ACK would have data";

  const auto pe = hex("52 45 84 9b 13");
  EXPECT_EQ(decode_reply(pe, {Command::execute, false}).value.status, Status::permission_error);
  const auto rc = hex("52 43 06 f7 08");
  EXPECT_TRUE(decode_reply(rc, {Command::cyclic, false}).ok());
}

TEST(ScuCodec, DecodesTheNotesRequestVectors) {
  const auto rt_bytes = hex("52 54 06 00 22 30 38 ff ff ff e5 e1");  // the decoded value points into it
  const auto rt = decode_request(rt_bytes);
  ASSERT_TRUE(rt.ok());
  const auto& t = std::get<TransferRequest>(rt.value);
  EXPECT_EQ(t.data_id, 0x3022);
  EXPECT_EQ(wire::to_hex(t.value), "38 ff ff ff");
  const auto re = decode_request(hex("52 45 00 09 ff 00 27"));
  ASSERT_TRUE(re.ok());
  EXPECT_EQ(std::get<ExecuteRequest>(re.value).direction, 9);
  const auto ro = decode_request(hex("52 4f 00 5c 2d"));
  ASSERT_TRUE(ro.ok());
  EXPECT_EQ(std::get<OpenRequest>(ro.value).safety_id, 0);
  const auto rc = decode_request(hex("52 43 01 00 ff 31 8d"));
  ASSERT_TRUE(rc.ok());
  EXPECT_EQ(std::get<CyclicRequest>(rc.value).index, kNoCyclicObject);
  EXPECT_TRUE(std::holds_alternative<AbortRequest>(decode_request(hex("52 41 38 30")).value));
}

TEST(ScuCodec, AllFiveErrorRepliesRoundTrip) {
  for (auto s : {Status::checksum_error, Status::parameter_data_error, Status::parameter_count_error,
                 Status::invalid_command, Status::permission_error}) {
    ReplyBytes out;
    ASSERT_TRUE(encode_reply(Reply{Command::cyclic, s, true, {}}, out));
    EXPECT_EQ(out.size(), 5u);
    const auto d = decode_reply(out.view(), {Command::cyclic, true});
    ASSERT_TRUE(d.ok()) << to_string(s);
    EXPECT_EQ(d.value.status, s);
  }
}

TEST(ScuCodec, EveryRequestRoundTrips) {
  const std::uint8_t write[] = {1, 2, 3, 4, 5, 6};
  const std::uint8_t value[24] = {0x11, 0x00, 0x70, 0x01};
  const Request all[] = {
      OpenRequest{2},
      AbortRequest{},
      CyclicRequest{},
      CyclicRequest{0, {}},
      CyclicRequest{4, write},
      GetRequest{0x0010},
      TransferRequest{0x3001, value},
      ExecuteRequest{3, 1, 1},
      ExecuteRequest{19, 0xFF, 0xFF},
      StopRequest{9, 0},
  };
  for (const auto& r : all) {
    RequestBytes out;
    ASSERT_TRUE(encode_request(r, out));
    const auto d = decode_request(out.view());
    ASSERT_TRUE(d.ok()) << wire::to_hex(out.view());
    RequestBytes again;
    ASSERT_TRUE(encode_request(d.value, again));
    EXPECT_EQ(again, out);
    EXPECT_EQ(command_of(d.value), command_of(r));
  }
}

TEST(ScuCodec, RcWithCyclicObjectCarriesCtpInItsReply) {
  EXPECT_EQ(reply_shape(CyclicRequest{}), (ReplyShape{Command::cyclic, false}));
  EXPECT_EQ(reply_shape(CyclicRequest{0, {}}), (ReplyShape{Command::cyclic, true}));
  EXPECT_EQ(reply_shape(GetRequest{0x11}), (ReplyShape{Command::get, true}));
  RequestBytes rc;
  ASSERT_TRUE(encode_request(CyclicRequest{0, {}}, rc));
  EXPECT_EQ(wire::to_hex(rc.view().first(5)), "52 43 01 00 00") << "ctp counts the index byte";
  EXPECT_TRUE(crc_ok(rc.view()));
  const std::uint8_t data[] = {0xb0, 0x01, 0x00, 0x00, 0x31};
  ReplyBytes out;
  ASSERT_TRUE(encode_reply(Reply{Command::cyclic, Status::ack, true, data}, out));
  EXPECT_EQ(out.size(), 5u + 2u + 5u);
  const auto d = decode_reply(out.view(), {Command::cyclic, true});
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(wire::to_hex(d.value.data), "b0 01 00 00 31");
}

TEST(ScuCodec, BadBytesGiveTypedErrors) {
  auto frame = hex("52 47 06 04 00 b0 01 00 00 ed 9a");
  frame[6] ^= 0x01;
  EXPECT_EQ(decode_reply(frame, {Command::get, true}).error, DecodeError::bad_crc);
  EXPECT_EQ(decode_reply(hex("52 54 06 13 92"), {Command::get, true}).error, DecodeError::unexpected_command);
  EXPECT_EQ(decode_reply(hex("52 47 07 00 00"), {Command::get, true}).error, DecodeError::bad_status);
  EXPECT_EQ(decode_reply(hex("53 47 06 00 00"), {Command::get, true}).error, DecodeError::bad_start);
  EXPECT_EQ(decode_reply(hex("52 58 06 00 00"), {Command::get, true}).error, DecodeError::unknown_command);
  EXPECT_EQ(decode_reply(hex("52 47 06 ff ff"), {Command::get, true}).error, DecodeError::bad_length);
  EXPECT_EQ(decode_reply(hex("52 47 06 04 00 b0 01"), {Command::get, true}).error, DecodeError::bad_length);
  EXPECT_EQ(decode_request(hex("52 4f 00 5c 2e")).error, DecodeError::bad_crc);
  EXPECT_EQ(decode_request(hex("52 5a 00 00")).error, DecodeError::unknown_command);
  EXPECT_EQ(decode_request(hex("52 54 ff 00")).error, DecodeError::bad_length) << "ctp beyond any request";
  // An RT whose ctp leaves no room for the data ID: framed, CRC good, still a count error.
  RequestBytes rt;
  const std::uint8_t body[] = {0x52, 0x54, 0x01, 0x00, 0x11};
  const auto c = crc16(body);
  for (auto b : body) rt.push_back(b);
  rt.push_back(static_cast<std::uint8_t>(c & 0xFF));
  rt.push_back(static_cast<std::uint8_t>(c >> 8));
  EXPECT_EQ(decode_request(rt.view()).error, DecodeError::bad_length);
}

TEST(ScuCodec, EncodersRefuseWhatTheWireCannotCarry) {
  std::vector<std::uint8_t> big(kMaxRequestData);
  RequestBytes out;
  EXPECT_FALSE(encode_request(TransferRequest{0x3001, big}, out));
  EXPECT_TRUE(out.empty());
  std::vector<std::uint8_t> huge(kMaxReplyData + 1);
  ReplyBytes r;
  EXPECT_FALSE(encode_reply(Reply{Command::get, Status::ack, true, huge}, r));
}

}  // namespace
}  // namespace cellctl::scu

// spindle::Codec against the manual's three worked examples (chapter 6, protocol-notes.md), round trips
// of every message, and a stream decoder that survives garbage, bad checksums and cut-off frames.

#include "spindle/codec.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cellctl::spindle {
namespace {

// STX + text + ETX, the way the manual writes frames.
std::vector<std::uint8_t> frame(const std::string& text) {
  std::vector<std::uint8_t> out{kStx};
  for (char c : text)
    if (c != ' ') out.push_back(static_cast<std::uint8_t>(c));
  out.push_back(kEtx);
  return out;
}

std::vector<std::uint8_t> encode(const Message& m) {
  std::vector<std::uint8_t> out(kMaxFrameLength);
  out.resize(Codec::encode(m, out));
  return out;
}

const std::string kManualStatusText =
    "01591b 00a7 0320 0000 00a7 0000 0230 02b2 0071 005a 00 0000010d 00000006 ab";

TEST(SpindleCodec, ChecksumIsTheLowByteOfTheAsciiSum) {
  const std::string text = "01cf0159";  // 0x30+0x31+0x63+0x66+0x30+0x31+0x35+0x39 = 0x1f9
  EXPECT_EQ(Codec::checksum(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())),
            0xf9);
}

TEST(SpindleCodec, EncodesTheManualsStatusRequest) {
  EXPECT_EQ(encode(Request{MsgId::res_status}), frame("01cf0159f9"));
}

TEST(SpindleCodec, EncodesTheManualsGrundparameterExample) {
  EXPECT_EQ(encode(SetBasic{400, SpeedUnit::hz}), frame("01100401900001b1"));
}

TEST(SpindleCodec, DecodesTheManualsStatusResponseIntoItsValues) {
  const auto d = Codec::decode_frame(frame(kManualStatusText));
  ASSERT_TRUE(d.ok()) << to_string(d.error);
  const auto& v = std::get<StatusValues>(d.message);
  EXPECT_EQ(v.set_frequency_hz, 167);             // P10
  EXPECT_DOUBLE_EQ(v.peak_current_a(), 8.00);     // P11
  EXPECT_EQ(v.actual_frequency_hz, 167);          // P13
  EXPECT_DOUBLE_EQ(v.motor_voltage_v(), 5.60);    // P15
  EXPECT_DOUBLE_EQ(v.dc_link_voltage_v(), 6.90);  // P16
  EXPECT_DOUBLE_EQ(v.motor_current_a(), 1.13);    // P18
  EXPECT_DOUBLE_EQ(v.power_w(), 9.0);             // P19
  EXPECT_EQ(v.motor_code, 0);                     // P20
  EXPECT_EQ(v.converter_hours, 269u);             // P25
  EXPECT_EQ(v.motor_hours, 6u);                   // P26
  // …and encoding those values gives back the manual's bytes, checksum "ab" included.
  EXPECT_EQ(encode(v), frame(kManualStatusText));
}

TEST(SpindleCodec, EncodesEveryRequestAndAck) {
  EXPECT_EQ(encode(Request{MsgId::res_ident}), frame("01cf015a21"));
  EXPECT_EQ(encode(Request{MsgId::res_statusout}), frame("01cf0160f1"));
  EXPECT_EQ(encode(Command{MsgId::cmd_start}), frame("01a00052"));
  EXPECT_EQ(encode(Command{MsgId::cmd_stop}), frame("01a10053"));
  EXPECT_EQ(encode(Command{MsgId::cmd_reset}), frame("01a20054"));
  EXPECT_EQ(encode(Ack{MsgId::set_basic}), frame("01ff0110ef"));
  EXPECT_EQ(encode(SetStart{Source::sycodrive, Source::sycodrive, Direction::counter_clockwise}),
            frame("01180301010251"));
}

TEST(SpindleCodec, EveryMessageRoundTrips) {
  const Message messages[] = {
      SetBasic{60000, SpeedUnit::rpm},
      SetStart{Source::can, Source::analog_current, Direction::digital_input},
      Command{MsgId::cmd_reset},
      Request{MsgId::res_statusout},
      Ack{MsgId::set_start},
      StatusValues{400, 800, 399, 2000, 4800, 100, 180, 3, 0x01020304, 0xfffffffe},
      Identification{{31, 51, 0, 0, 0}, 4624, 0x0433, 123456789},
      StatusOut{21, DeviceState::warning, StatusOut::kAtSpeedFlag | StatusOut::kCurrentLimitFlag, 1},
  };
  for (const auto& m : messages) {
    const auto bytes = encode(m);
    ASSERT_FALSE(bytes.empty());
    const auto d = Codec::decode_frame(bytes);
    ASSERT_TRUE(d.ok()) << to_string(d.error) << " for MSGID " << int(id_of(m));
    EXPECT_EQ(d.message, m);
  }
}

TEST(SpindleCodec, EncodeRefusesASmallBuffer) {
  std::array<std::uint8_t, 12> small{};
  EXPECT_EQ(Codec::encode(Request{MsgId::res_status}, small), 12u);  // STX, 10 characters, ETX: fits
  std::array<std::uint8_t, 11> smaller{};
  EXPECT_EQ(Codec::encode(Request{MsgId::res_status}, smaller), 0u);
}

Decoded decode(const std::string& text) {
  return Codec::decode_frame(frame(text));
}

TEST(SpindleCodec, RejectsBadFramesWithTypedErrors) {
  EXPECT_EQ(decode("01cf0159f8").error, DecodeError::bad_checksum);
  EXPECT_EQ(decode("01CF0159f9").error, DecodeError::bad_hex_digit);  // the wire is lowercase only
  EXPECT_EQ(decode("01cf01x9f9").error, DecodeError::bad_hex_digit);
  EXPECT_EQ(decode("02cf0159fa").error, DecodeError::bad_version);
  EXPECT_EQ(decode("01cc0159f6").error, DecodeError::unknown_message);
  EXPECT_EQ(decode("01cf025900fb").error, DecodeError::wrong_length);  // REQ carries one byte
  EXPECT_EQ(decode("01cf01").error, DecodeError::wrong_length);        // ETX too early
  EXPECT_EQ(decode("01cf0159f9f9").error, DecodeError::missing_etx);
  EXPECT_EQ(decode("01cf0110ec").error, DecodeError::bad_value);  // REQ for a non-response
  EXPECT_EQ(decode("0110040190000363").error, DecodeError::bad_checksum);
  EXPECT_EQ(decode("01100401900003b3").error, DecodeError::bad_value);  // P8 = 3 is undefined
  EXPECT_EQ(decode("01600400040000af").error, DecodeError::bad_value);  // statusout2 = 4 undefined
}

struct Collected {
  std::vector<Decoded> results;
  std::uint64_t skipped = 0;
};

Collected feed(const std::vector<std::uint8_t>& bytes) {
  FrameDecoder decoder;
  Collected out;
  for (auto b : bytes)
    if (auto d = decoder.push(b)) out.results.push_back(*d);
  out.skipped = decoder.skipped_bytes();
  return out;
}

std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

TEST(SpindleFrameDecoder, SkipsNoiseBetweenFrames) {
  const auto got = feed(concat({{0x00, 0xff, 'x', kEtx}, frame("01cf0159f9"), {0x55}, frame("01a00052")}));
  ASSERT_EQ(got.results.size(), 2u);
  EXPECT_EQ(got.results[0].message, Message{Request{MsgId::res_status}});
  EXPECT_EQ(got.results[1].message, Message{Command{MsgId::cmd_start}});
  EXPECT_EQ(got.skipped, 5u);
}

TEST(SpindleFrameDecoder, ResynchronisesOnStxInsideAFrame) {
  // A frame cut off by line noise, then a complete one: the first is reported, the second survives.
  const auto got = feed(concat({{kStx, '0', '1', 'c'}, frame("01a10053")}));
  ASSERT_EQ(got.results.size(), 2u);
  EXPECT_EQ(got.results[0].error, DecodeError::interrupted);
  EXPECT_EQ(got.results[1].message, Message{Command{MsgId::cmd_stop}});
}

TEST(SpindleFrameDecoder, ABadChecksumDoesNotCostTheNextFrame) {
  const auto got = feed(concat({frame("01cf0159f8"), frame("01cf0159f9")}));
  ASSERT_EQ(got.results.size(), 2u);
  EXPECT_EQ(got.results[0].error, DecodeError::bad_checksum);
  EXPECT_TRUE(got.results[1].ok());
}

TEST(SpindleFrameDecoder, SkipsTheRestOfARejectedFrame) {
  // Unknown MSGID: rejected at the header, its remaining characters are skipped up to the next STX.
  const auto got = feed(concat({frame("01cc0159f6"), frame("01a20054")}));
  ASSERT_EQ(got.results.size(), 2u);
  EXPECT_EQ(got.results[0].error, DecodeError::unknown_message);
  EXPECT_EQ(got.results[1].message, Message{Command{MsgId::cmd_reset}});
  EXPECT_EQ(got.skipped, 5u);  // "59f6" and ETX
}

TEST(SpindleFrameDecoder, DecodesAFrameSplitAcrossManyPushesAndEveryTruncation) {
  const auto full = frame(kManualStatusText);
  // Every proper prefix of the frame followed by a good frame: never a false message, always resyncs.
  for (std::size_t cut = 1; cut < full.size(); ++cut) {
    std::vector<std::uint8_t> bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut));
    const auto got = feed(concat({bytes, frame("01a00052")}));
    ASSERT_FALSE(got.results.empty());
    EXPECT_EQ(got.results.back().message, Message{Command{MsgId::cmd_start}}) << "cut at " << cut;
    for (std::size_t i = 0; i + 1 < got.results.size(); ++i) EXPECT_FALSE(got.results[i].ok());
  }
}

TEST(SpindleFrameDecoder, NoSingleBitErrorYieldsADifferentMessage) {
  // Flipping one bit anywhere in a frame must never yield a *different* valid message.
  const auto good = frame(kManualStatusText);
  const auto original = Codec::decode_frame(good);
  for (std::size_t i = 0; i < good.size(); ++i) {
    for (unsigned bit = 0; bit < 8; ++bit) {
      auto bad = good;
      bad[i] = static_cast<std::uint8_t>(bad[i] ^ (1u << bit));
      const auto got = feed(bad);
      for (const auto& d : got.results)
        EXPECT_FALSE(d.ok() && !(d.message == original.message)) << i << "/" << bit;
    }
  }
}

}  // namespace
}  // namespace cellctl::spindle

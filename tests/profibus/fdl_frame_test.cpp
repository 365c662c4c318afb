// FDL frames byte-exact against protocol-notes.md, the SD1/SD2/SD3 choice, FCS/length/end-delimiter
// errors, and the stream decoder's resynchronisation after garbage and torn frames.

#include "profibus/fdl_frame.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "profibus/fdl_codes.hpp"
#include "profibus/fdl_decoder.hpp"
#include "wire/hex.hpp"

namespace cellctl::profibus {
namespace {

std::vector<std::uint8_t> bytes(std::string_view hex) {
  return *wire::parse_hex(hex);
}

std::string encoded(const FdlFrame& f) {
  std::array<std::uint8_t, kMaxFrameSize> out{};
  const std::size_t n = encode(f, out);
  return wire::to_hex(std::span<const std::uint8_t>(out.data(), n));
}

FdlParse parse(std::string_view hex) {
  const auto b = bytes(hex);
  return parse_frame(b);
}

TEST(FdlFrame, FdlStatusRequestVector) {
  // Master 2 → slave 5, FDL_Status: SD1.
  const FdlFrame f = make_frame(5, 2, fc::kRequest | fc::kFdlStatus);
  EXPECT_EQ(encoded(f), "10 05 02 49 50 16");
  const FdlParse p = parse("10 05 02 49 50 16");
  ASSERT_EQ(p.status, FdlParse::Status::frame);
  EXPECT_EQ(p.consumed, 6u);
  EXPECT_EQ(p.frame.kind, FrameKind::sd1);
  EXPECT_EQ(p.frame.da, 5);
  EXPECT_EQ(p.frame.sa, 2);
  EXPECT_EQ(p.frame.fc, 0x49);
  EXPECT_FALSE(p.frame.dsap);
}

TEST(FdlFrame, SlaveDiagRequestVector) {
  // SAP 62 → 60, FCB 1, FCV 0, SRD_HI: SD2 with the address extension bits.
  const FdlFrame f =
      make_sap_frame(5, 2, fc::kRequest | fc::kFcb | fc::kSrdHigh, sap::kSlaveDiag, sap::kMaster);
  EXPECT_EQ(encoded(f), "68 05 05 68 85 82 6d 3c 3e ee 16");
  const FdlParse p = parse("68 05 05 68 85 82 6d 3c 3e ee 16");
  ASSERT_EQ(p.status, FdlParse::Status::frame);
  FdlFrame expected = f;
  expected.kind = FrameKind::sd2;
  EXPECT_EQ(p.frame, expected);
  EXPECT_EQ(p.frame.kind, FrameKind::sd2);
  EXPECT_EQ(p.frame.da, 5);
  EXPECT_EQ(p.frame.sa, 2);
  EXPECT_EQ(p.frame.fc, 0x6d);
  EXPECT_EQ(p.frame.dsap, std::optional<std::uint8_t>(60));
  EXPECT_EQ(p.frame.ssap, std::optional<std::uint8_t>(62));
  EXPECT_TRUE(p.frame.data.empty());
}

TEST(FdlFrame, EightOctetDataUnitUsesSd3BothWays) {
  // Data_Exchange reply with the encoder's 8 input octets (Scancon 3.0): SD3, no LE.
  const std::vector<std::uint8_t> in{0x06, 0x00, 0x12, 0x34, 0x00, 0x10, 0xff, 0xfe};
  const FdlFrame f = make_frame(2, 5, fc::kDataLow, in);
  const std::string hex = encoded(f);
  EXPECT_EQ(hex, "a2 02 05 08 06 00 12 34 00 10 ff fe 68 16");
  const FdlParse p = parse(hex);
  ASSERT_EQ(p.status, FdlParse::Status::frame);
  EXPECT_EQ(p.frame.kind, FrameKind::sd3);
  EXPECT_EQ(p.frame.da, 2);
  EXPECT_EQ(p.frame.sa, 5);
  EXPECT_TRUE(std::ranges::equal(p.frame.data.view(), in));

  // SAPs count towards the 8 octets: DSAP SSAP + 6 data → SD3 with the extension bits.
  const std::vector<std::uint8_t> six{1, 2, 3, 4, 5, 6};
  const FdlFrame s = make_sap_frame(2, 5, fc::kDataLow, 62, 60, six);
  const FdlParse ps = parse(encoded(s));
  ASSERT_EQ(ps.status, FdlParse::Status::frame);
  EXPECT_EQ(ps.frame.kind, FrameKind::sd3);
  EXPECT_EQ(ps.frame.dsap, std::optional<std::uint8_t>(62));
  EXPECT_EQ(ps.frame.ssap, std::optional<std::uint8_t>(60));
  EXPECT_TRUE(std::ranges::equal(ps.frame.data.view(), six));
}

TEST(FdlFrame, Sd2AndSd3BothParseToTheSameContent) {
  // A sender that (wrongly) used SD2 for 8 octets is still understood.
  const FdlParse sd3 = parse("a2 02 05 08 01 02 03 04 05 06 07 08 33 16");
  const FdlParse sd2 = parse("68 0b 0b 68 02 05 08 01 02 03 04 05 06 07 08 33 16");
  ASSERT_EQ(sd3.status, FdlParse::Status::frame);
  ASSERT_EQ(sd2.status, FdlParse::Status::frame);
  EXPECT_EQ(sd3.frame.kind, FrameKind::sd3);
  EXPECT_EQ(sd2.frame.kind, FrameKind::sd2);
  EXPECT_EQ(sd3.frame.data, sd2.frame.data);
  EXPECT_EQ(sd3.frame.fc, sd2.frame.fc);
}

TEST(FdlFrame, RoundTripsEveryDataUnitLength) {
  for (std::size_t n = 0; n <= kMaxData; ++n) {
    std::vector<std::uint8_t> data(n);
    for (std::size_t i = 0; i < n; ++i) data[i] = static_cast<std::uint8_t>(i * 37 + 1);
    const FdlFrame f = n % 2 ? make_frame(9, 1, 0x5d, data) : make_sap_frame(9, 1, 0x7d, 61, 62, data);
    std::array<std::uint8_t, kMaxFrameSize> out{};
    const std::size_t len = encode(f, out);
    ASSERT_GT(len, 0u) << n;
    ASSERT_EQ(len, encoded_size(f));
    const FdlParse p = parse_frame(std::span<const std::uint8_t>(out.data(), len));
    ASSERT_EQ(p.status, FdlParse::Status::frame) << n;
    EXPECT_EQ(p.consumed, len);
    FdlFrame expected = f;
    expected.kind = p.frame.kind;
    EXPECT_EQ(p.frame, expected) << n;
  }
}

TEST(FdlFrame, ShortAckTokenAndOversizeFrames) {
  EXPECT_EQ(encoded(make_short_ack()), "e5");
  EXPECT_EQ(parse("e5").frame.kind, FrameKind::short_ack);
  const FdlParse tok = parse("dc 05 02");
  EXPECT_EQ(tok.frame.kind, FrameKind::token);
  EXPECT_EQ(tok.consumed, 3u);
  FdlFrame bad = make_frame(128, 2, 0x49);
  std::array<std::uint8_t, kMaxFrameSize> out{};
  EXPECT_EQ(encode(bad, out), 0u) << "address above 127";
  std::array<std::uint8_t, 5> tiny{};
  EXPECT_EQ(encode(make_frame(5, 2, 0x49), tiny), 0u) << "buffer too small";
}

TEST(FdlFrame, TypedErrors) {
  EXPECT_EQ(parse("10 05 02 49 51 16").error, FdlError::bad_fcs);
  EXPECT_EQ(parse("10 05 02 49 50 17").error, FdlError::bad_end_delimiter);
  EXPECT_EQ(parse("68 05 06 68 85 82 6d 3c 3e ee 16").error, FdlError::length_mismatch);
  EXPECT_EQ(parse("68 02 02 68").error, FdlError::bad_length);
  EXPECT_EQ(parse("68 fa").error, FdlError::bad_length);
  EXPECT_EQ(parse("00 11 22 10").error, FdlError::garbage);
  EXPECT_EQ(parse("00 11 22 10").consumed, 3u);
  EXPECT_EQ(parse("68 05 05 68 85 82").status, FdlParse::Status::need_more);
  // DA and SA both say a SAP follows, but the data unit holds only the DSAP.
  EXPECT_EQ(parse("68 04 04 68 85 82 6d 3c b0 16").error, FdlError::bad_sap);
}

// An SD2 frame built by hand: LE = 3 + du octets, the FCS over DA..DU.
std::vector<std::uint8_t> sd2(std::uint8_t da, std::uint8_t sa, std::uint8_t fc, std::size_t du) {
  std::vector<std::uint8_t> f{
      kSd2, static_cast<std::uint8_t>(3 + du), static_cast<std::uint8_t>(3 + du), kSd2, da, sa, fc};
  for (std::size_t i = 0; i < du; ++i) f.push_back(static_cast<std::uint8_t>(i));
  std::uint8_t fcs = 0;
  for (std::size_t i = 4; i < f.size(); ++i) fcs = static_cast<std::uint8_t>(fcs + f[i]);
  f.push_back(fcs);
  f.push_back(kEndDelimiter);
  return f;
}

TEST(FdlFrame, DataBeyond244OctetsIsRefusedNeverCut) {
  // LE 249 is in the standard's range, but without SAPs it carries 246 data octets: DP allows 244.
  const auto le249 = sd2(2, 5, 0x08, 246);
  const FdlParse p = parse_frame(le249);
  EXPECT_EQ(p.status, FdlParse::Status::error);
  EXPECT_EQ(p.error, FdlError::data_too_long);
  EXPECT_EQ(p.consumed, le249.size()) << "the whole frame is dropped, the next one parses";
  // 245 data octets (LE 248) too; 244 (LE 247) is the longest a Data_Exchange may carry.
  EXPECT_EQ(parse_frame(sd2(2, 5, 0x08, 245)).error, FdlError::data_too_long);
  const FdlParse ok = parse_frame(sd2(2, 5, 0x08, 244));
  ASSERT_EQ(ok.status, FdlParse::Status::frame);
  EXPECT_EQ(ok.frame.data.size(), 244u);
  // With both SAPs LE 249 leaves exactly 244 data octets: valid.
  auto with_saps = sd2(2 | kAddressExtension, 5 | kAddressExtension, 0x08, 246);
  EXPECT_EQ(parse_frame(with_saps).status, FdlParse::Status::frame);
  // LE beyond 249 never gets that far.
  EXPECT_EQ(parse("68 fa fa 68").error, FdlError::bad_length);
  EXPECT_EQ(parse("68 03 03 68").error, FdlError::bad_length);

  // In a stream: refused, counted as an error event, and the frame behind it still arrives.
  FdlDecoder d;
  auto stream = le249;
  const auto status = bytes("10 05 02 49 50 16");
  stream.insert(stream.end(), status.begin(), status.end());
  ASSERT_EQ(d.push(stream), stream.size());
  const auto first = d.next();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->error, FdlError::data_too_long);
  const auto second = d.next();
  ASSERT_TRUE(second);
  EXPECT_EQ(second->error, FdlError::none);
  EXPECT_EQ(second->frame.fc, 0x49);
}

TEST(FdlDecoder, FramesInAnyPiecesAndResynchronisesAfterGarbage) {
  const auto stream = bytes(
      "ff 00 "                             // line noise
      "10 05 02 49 50 16 "                 // FDL_Status
      "68 05 05 68 85 82 6d 3c 3e ef 16 "  // Slave_Diag with a wrong FCS
      "68 05 05 68 85 "                    // torn frame: the rest never came
      "68 05 05 68 85 82 6d 3c 3e ee 16 "  // Slave_Diag
      "e5");
  for (std::size_t piece : {std::size_t{1}, std::size_t{3}, std::size_t{7}, stream.size()}) {
    FdlDecoder d;
    std::vector<FdlEvent> events;
    for (std::size_t i = 0; i < stream.size(); i += piece) {
      const auto n = std::min(piece, stream.size() - i);
      ASSERT_EQ(d.push(std::span<const std::uint8_t>(stream).subspan(i, n)), n);
      while (auto ev = d.next()) events.push_back(*ev);
    }
    std::vector<FrameKind> frames;
    int errors = 0;
    bool fcs_seen = false;
    for (const auto& ev : events) {
      if (ev.error == FdlError::none)
        frames.push_back(ev.frame.kind);
      else
        ++errors;
      fcs_seen = fcs_seen || ev.error == FdlError::bad_fcs;
    }
    EXPECT_EQ(frames, (std::vector<FrameKind>{FrameKind::sd1, FrameKind::sd2, FrameKind::short_ack}))
        << "piece " << piece;
    EXPECT_TRUE(fcs_seen);
    EXPECT_GE(errors, 3) << "garbage, bad FCS and the torn frame are each reported";
    EXPECT_EQ(d.buffered(), 0u);
  }
}

TEST(FdlDecoder, ResetForgetsATornFrame) {
  FdlDecoder d;
  const auto torn = bytes("68 05 05 68 85 82");
  (void)d.push(torn);
  EXPECT_FALSE(d.next());
  d.reset();
  const auto good = bytes("10 05 02 49 50 16");
  (void)d.push(good);
  const auto ev = d.next();
  ASSERT_TRUE(ev);
  EXPECT_EQ(ev->error, FdlError::none);
  EXPECT_EQ(ev->frame.fc, 0x49);
}

}  // namespace
}  // namespace cellctl::profibus

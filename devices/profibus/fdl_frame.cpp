#include "profibus/fdl_frame.hpp"

#include "profibus/fdl_codes.hpp"
#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"
#include "wire/octet_sum.hpp"

namespace cellctl::profibus {

std::string_view to_string(FrameKind k) noexcept {
  switch (k) {
    case FrameKind::sd1:
      return "SD1";
    case FrameKind::sd2:
      return "SD2";
    case FrameKind::sd3:
      return "SD3";
    case FrameKind::token:
      return "SD4";
    case FrameKind::short_ack:
      return "SC";
  }
  return "?";
}

std::string_view to_string(FdlError e) noexcept {
  switch (e) {
    case FdlError::none:
      return "none";
    case FdlError::garbage:
      return "garbage before a start delimiter";
    case FdlError::bad_length:
      return "SD2 length outside 4..249";
    case FdlError::length_mismatch:
      return "SD2 LE and LEr differ";
    case FdlError::bad_fcs:
      return "frame check sequence wrong";
    case FdlError::bad_end_delimiter:
      return "end delimiter missing";
    case FdlError::bad_sap:
      return "address extension without SAP octet";
    case FdlError::data_too_long:
      return "data unit longer than the 244 octets DP allows";
  }
  return "?";
}

FdlFrame make_frame(std::uint8_t da, std::uint8_t sa, std::uint8_t fc,
                    std::span<const std::uint8_t> data) noexcept {
  FdlFrame f;
  f.da = da;
  f.sa = sa;
  f.fc = fc;
  (void)f.data.assign(data);  // every caller's is a DP data unit: at most kMaxData octets
  return f;
}

FdlFrame make_sap_frame(std::uint8_t da, std::uint8_t sa, std::uint8_t fc, std::uint8_t dsap,
                        std::uint8_t ssap, std::span<const std::uint8_t> data) noexcept {
  FdlFrame f = make_frame(da, sa, fc, data);
  f.dsap = dsap;
  f.ssap = ssap;
  return f;
}

FdlFrame make_short_ack() noexcept {
  FdlFrame f;
  f.kind = FrameKind::short_ack;
  return f;
}

namespace {

// The frame type the standard prescribes for this data unit.
FrameKind data_frame_kind(const FdlFrame& frame) noexcept {
  const std::size_t du = frame.data_unit_size();
  if (du == 0) return FrameKind::sd1;
  if (du == kSd3DataUnit) return FrameKind::sd3;
  return FrameKind::sd2;
}

bool is_start_delimiter(std::uint8_t b) noexcept {
  return b == kSd1 || b == kSd2 || b == kSd3 || b == kSd4 || b == kShortAck;
}

// DA SA FC [DSAP SSAP] DU: the octets the FCS covers.
void write_body(const FdlFrame& f, wire::ByteWriter& w) noexcept {
  w.u8(static_cast<std::uint8_t>(f.da | (f.dsap ? kAddressExtension : 0u)));
  w.u8(static_cast<std::uint8_t>(f.sa | (f.ssap ? kAddressExtension : 0u)));
  w.u8(f.fc);
  if (f.dsap) w.u8(*f.dsap);
  if (f.ssap) w.u8(*f.ssap);
  for (auto b : f.data.view()) w.u8(b);
}

}  // namespace

std::size_t encoded_size(const FdlFrame& frame) noexcept {
  if (frame.kind == FrameKind::short_ack) return 1;
  if (frame.kind == FrameKind::token) return 3;
  if (frame.da > 127 || frame.sa > 127) return 0;
  const std::size_t du = frame.data_unit_size();
  switch (data_frame_kind(frame)) {
    case FrameKind::sd1:
      return 6;
    case FrameKind::sd3:
      return 14;
    default:
      return 3 + du > kMaxSd2Length ? 0 : 4 + 3 + du + 2;
  }
}

std::size_t encode(const FdlFrame& frame, std::span<std::uint8_t> out) noexcept {
  const std::size_t size = encoded_size(frame);
  if (size == 0 || size > out.size()) return 0;
  wire::ByteWriter w(out);
  if (frame.kind == FrameKind::short_ack) {
    w.u8(kShortAck);
    return w.size();
  }
  if (frame.kind == FrameKind::token) {
    w.u8(kSd4);
    w.u8(frame.da);
    w.u8(frame.sa);
    return w.size();
  }
  switch (data_frame_kind(frame)) {
    case FrameKind::sd1:
      w.u8(kSd1);
      break;
    case FrameKind::sd3:
      w.u8(kSd3);
      break;
    default: {
      const auto le = static_cast<std::uint8_t>(3 + frame.data_unit_size());
      w.u8(kSd2);
      w.u8(le);
      w.u8(le);
      w.u8(kSd2);
    }
  }
  const std::size_t body_start = w.size();
  write_body(frame, w);
  w.u8(wire::octet_sum(w.written().subspan(body_start)));
  w.u8(kEndDelimiter);
  return w.ok() ? w.size() : 0;
}

namespace {

FdlParse error(FdlError e, std::size_t consumed) noexcept {
  FdlParse p;
  p.status = FdlParse::Status::error;
  p.error = e;
  p.consumed = consumed;
  return p;
}

// Parses DA SA FC [DSAP SSAP] DU from `body` (the octets the FCS covers).
FdlParse parse_body(std::span<const std::uint8_t> body, FrameKind kind, std::size_t total) noexcept {
  FdlParse p;
  p.frame.kind = kind;
  wire::ByteReader r(body);
  const std::uint8_t da = r.u8();
  const std::uint8_t sa = r.u8();
  p.frame.fc = r.u8();
  p.frame.da = da & 0x7Fu;
  p.frame.sa = sa & 0x7Fu;
  if ((da & kAddressExtension) != 0) {
    if (r.remaining() < 1) return error(FdlError::bad_sap, total);
    p.frame.dsap = r.u8();
  }
  if ((sa & kAddressExtension) != 0) {
    if (r.remaining() < 1) return error(FdlError::bad_sap, total);
    p.frame.ssap = r.u8();
  }
  if (!p.frame.data.assign(r.rest())) return error(FdlError::data_too_long, total);
  p.status = FdlParse::Status::frame;
  p.consumed = total;
  return p;
}

// A frame whose body is bytes[offset, offset+len) followed by FCS and ED.
FdlParse parse_framed(std::span<const std::uint8_t> bytes, std::size_t offset, std::size_t len,
                      FrameKind kind) noexcept {
  const std::size_t total = offset + len + 2;
  if (bytes.size() < total) return {};
  if (bytes[total - 1] != kEndDelimiter) return error(FdlError::bad_end_delimiter, 1);
  const auto body = bytes.subspan(offset, len);
  if (wire::octet_sum(body) != bytes[offset + len]) return error(FdlError::bad_fcs, total);
  return parse_body(body, kind, total);
}

}  // namespace

FdlParse parse_frame(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.empty()) return {};
  if (!is_start_delimiter(bytes[0])) {
    std::size_t n = 1;
    while (n < bytes.size() && !is_start_delimiter(bytes[n])) ++n;
    return error(FdlError::garbage, n);
  }
  switch (bytes[0]) {
    case kShortAck: {
      FdlParse p;
      p.status = FdlParse::Status::frame;
      p.consumed = 1;
      p.frame = make_short_ack();
      return p;
    }
    case kSd4: {
      if (bytes.size() < 3) return {};
      FdlParse p;
      p.status = FdlParse::Status::frame;
      p.consumed = 3;
      p.frame.kind = FrameKind::token;
      p.frame.da = bytes[1] & 0x7Fu;
      p.frame.sa = bytes[2] & 0x7Fu;
      return p;
    }
    case kSd1:
      return parse_framed(bytes, 1, 3, FrameKind::sd1);
    case kSd3:
      return parse_framed(bytes, 1, 3 + kSd3DataUnit, FrameKind::sd3);
    default:
      break;  // SD2
  }
  if (bytes.size() < 4) {
    // Judge what is there already, so a torn header is dropped without waiting for more octets.
    if (bytes.size() >= 2 && (bytes[1] < kMinSd2Length || bytes[1] > kMaxSd2Length))
      return error(FdlError::bad_length, 1);
    if (bytes.size() >= 3 && bytes[2] != bytes[1]) return error(FdlError::length_mismatch, 1);
    return {};
  }
  const std::uint8_t le = bytes[1];
  if (le < kMinSd2Length || le > kMaxSd2Length) return error(FdlError::bad_length, 1);
  if (bytes[2] != le || bytes[3] != kSd2) return error(FdlError::length_mismatch, 1);
  return parse_framed(bytes, 4, le, FrameKind::sd2);
}

}  // namespace cellctl::profibus

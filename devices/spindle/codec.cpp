#include "spindle/codec.hpp"

#include <type_traits>

#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"
#include "wire/hex.hpp"
#include "wire/octet_sum.hpp"

namespace cellctl::spindle {
namespace {

constexpr std::size_t kHeaderTextLength = 6;  // VER, MSGID, LEN as text

// The manual allows only '0'..'9' and lowercase 'a'..'f' on the wire (4.1.2.2 ff.).
constexpr int wire_hex_value(std::uint8_t c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// The byte written by the hex pair at text[i], text[i+1] (both already checked).
constexpr std::uint8_t byte_at(std::span<const std::uint8_t> text, std::size_t i) noexcept {
  return static_cast<std::uint8_t>(wire_hex_value(text[i]) * 16 + wire_hex_value(text[i + 1]));
}

// Data bytes of one message, big-endian, into `w`; returns the MSGID.
MsgId write_data(const Message& message, wire::ByteWriter& w) noexcept {
  return std::visit(
      [&w](const auto& m) -> MsgId {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, SetBasic>) {
          w.be(m.frequency_hz);
          w.u8(0x00);  // unused
          w.u8(static_cast<std::uint8_t>(m.unit));
          return MsgId::set_basic;
        } else if constexpr (std::is_same_v<T, SetStart>) {
          w.u8(static_cast<std::uint8_t>(m.start_source));
          w.u8(static_cast<std::uint8_t>(m.setpoint_source));
          w.u8(static_cast<std::uint8_t>(m.direction));
          return MsgId::set_start;
        } else if constexpr (std::is_same_v<T, Command>) {
          return m.id;
        } else if constexpr (std::is_same_v<T, Request>) {
          w.u8(static_cast<std::uint8_t>(m.wanted));
          return MsgId::request;
        } else if constexpr (std::is_same_v<T, Ack>) {
          w.u8(static_cast<std::uint8_t>(m.acknowledged));
          return MsgId::ack;
        } else if constexpr (std::is_same_v<T, StatusValues>) {
          w.be(m.set_frequency_hz);
          w.be(m.peak_current_ca);
          w.be(std::uint16_t{0});  // unused
          w.be(m.actual_frequency_hz);
          w.be(std::uint16_t{0});  // unused
          w.be(m.motor_voltage_cv);
          w.be(m.dc_link_voltage_cv);
          w.be(m.motor_current_ca);
          w.be(m.power_dw);
          w.u8(m.motor_code);
          w.be(m.converter_hours);
          w.be(m.motor_hours);
          return MsgId::res_status;
        } else if constexpr (std::is_same_v<T, Identification>) {
          for (auto f : m.fault_history) w.u8(f);
          w.be(m.converter_type);
          w.be(m.firmware);
          w.be(m.serial_number);
          return MsgId::res_ident;
        } else {
          static_assert(std::is_same_v<T, StatusOut>);
          w.u8(m.error_number);
          w.u8(static_cast<std::uint8_t>(m.state));
          w.u8(m.flags);
          w.u8(m.motor_code);
          return MsgId::res_statusout;
        }
      },
      message);
}

constexpr bool is_command(std::uint8_t v) noexcept {
  return v >= 0xA0 && v <= 0xA2;
}
constexpr bool is_acknowledgeable(std::uint8_t v) noexcept {
  return v == 0x10 || v == 0x18 || is_command(v);
}
constexpr bool is_response(std::uint8_t v) noexcept {
  return v == 0x59 || v == 0x5A || v == 0x60;
}

Decoded bad_value() noexcept {
  return {DecodeError::bad_value, {}};
}

}  // namespace

MsgId id_of(const Message& m) noexcept {
  std::array<std::uint8_t, kMaxDataLength> scratch{};
  wire::ByteWriter w(scratch);
  return write_data(m, w);
}

std::string_view to_string(DecodeError e) noexcept {
  switch (e) {
    case DecodeError::none:
      return "none";
    case DecodeError::bad_hex_digit:
      return "bad hex digit";
    case DecodeError::bad_version:
      return "bad version";
    case DecodeError::unknown_message:
      return "unknown message id";
    case DecodeError::wrong_length:
      return "wrong length";
    case DecodeError::missing_etx:
      return "missing ETX";
    case DecodeError::interrupted:
      return "frame interrupted by STX";
    case DecodeError::bad_checksum:
      return "bad checksum";
    case DecodeError::bad_value:
      return "undefined field value";
  }
  return "?";
}

std::uint8_t Codec::checksum(std::span<const std::uint8_t> text) noexcept {
  return wire::octet_sum(text);
}

std::size_t Codec::encode(const Message& message, std::span<std::uint8_t> out) noexcept {
  std::array<std::uint8_t, 3 + kMaxDataLength> bytes{};
  wire::ByteWriter data{std::span<std::uint8_t>(bytes).subspan(3)};
  const MsgId id = write_data(message, data);
  bytes[0] = kVersion;
  bytes[1] = static_cast<std::uint8_t>(id);
  bytes[2] = static_cast<std::uint8_t>(data.size());
  const std::size_t n_bytes = 3 + data.size();
  const std::size_t frame_length = 1 + 2 * (n_bytes + 1) + 1;
  if (out.size() < frame_length) return 0;

  std::size_t pos = 0;
  out[pos++] = kStx;
  auto put_hex = [&](std::uint8_t b) {
    out[pos++] = static_cast<std::uint8_t>(wire::hex_digit(b >> 4u));
    out[pos++] = static_cast<std::uint8_t>(wire::hex_digit(b));
  };
  for (std::size_t i = 0; i < n_bytes; ++i) put_hex(bytes[i]);
  put_hex(checksum(out.subspan(1, pos - 1)));
  out[pos++] = kEtx;
  return pos;
}

Decoded Codec::decode_data(std::uint8_t id, std::span<const std::uint8_t> data) noexcept {
  if (data_length(id) < 0) return {DecodeError::unknown_message, {}};
  if (data.size() != static_cast<std::size_t>(data_length(id))) return {DecodeError::wrong_length, {}};
  wire::ByteReader r(data);
  switch (static_cast<MsgId>(id)) {
    case MsgId::set_basic: {
      SetBasic m;
      m.frequency_hz = r.be<std::uint16_t>();
      (void)r.u8();  // unused
      const auto unit = r.u8();
      if (unit != 0x01 && unit != 0x02) return bad_value();
      m.unit = static_cast<SpeedUnit>(unit);
      return {DecodeError::none, m};
    }
    case MsgId::set_start: {
      const auto start = r.u8(), setpoint = r.u8(), direction = r.u8();
      if (start < 0x01 || start > 0x03 || setpoint < 0x01 || setpoint > 0x05 || direction < 0x01 ||
          direction > 0x03)
        return bad_value();
      return {DecodeError::none, SetStart{static_cast<Source>(start), static_cast<Source>(setpoint),
                                          static_cast<Direction>(direction)}};
    }
    case MsgId::cmd_start:
    case MsgId::cmd_stop:
    case MsgId::cmd_reset:
      return {DecodeError::none, Command{static_cast<MsgId>(id)}};
    case MsgId::request: {
      const auto wanted = r.u8();
      if (!is_response(wanted)) return bad_value();
      return {DecodeError::none, Request{static_cast<MsgId>(wanted)}};
    }
    case MsgId::ack: {
      const auto acknowledged = r.u8();
      if (!is_acknowledgeable(acknowledged)) return bad_value();
      return {DecodeError::none, Ack{static_cast<MsgId>(acknowledged)}};
    }
    case MsgId::res_status: {
      StatusValues m;
      m.set_frequency_hz = r.be<std::uint16_t>();
      m.peak_current_ca = r.be<std::uint16_t>();
      (void)r.be<std::uint16_t>();  // unused
      m.actual_frequency_hz = r.be<std::uint16_t>();
      (void)r.be<std::uint16_t>();  // unused
      m.motor_voltage_cv = r.be<std::uint16_t>();
      m.dc_link_voltage_cv = r.be<std::uint16_t>();
      m.motor_current_ca = r.be<std::uint16_t>();
      m.power_dw = r.be<std::uint16_t>();
      m.motor_code = r.u8();
      m.converter_hours = r.be<std::uint32_t>();
      m.motor_hours = r.be<std::uint32_t>();
      return {DecodeError::none, m};
    }
    case MsgId::res_ident: {
      Identification m;
      for (auto& f : m.fault_history) f = r.u8();
      m.converter_type = r.be<std::uint16_t>();
      m.firmware = r.be<std::uint16_t>();
      m.serial_number = r.be<std::uint32_t>();
      return {DecodeError::none, m};
    }
    case MsgId::res_statusout: {
      StatusOut m;
      m.error_number = r.u8();
      const auto state = r.u8();
      if (state != 0x00 && state != 0x02 && state != 0x03) return bad_value();
      m.state = static_cast<DeviceState>(state);
      m.flags = r.u8();
      m.motor_code = r.u8();
      return {DecodeError::none, m};
    }
  }
  return {DecodeError::unknown_message, {}};
}

Decoded Codec::decode_frame(std::span<const std::uint8_t> frame) noexcept {
  FrameDecoder decoder;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (auto d = decoder.push(frame[i])) {
      // A frame that ends before the input does is not "exactly one frame".
      return i + 1 == frame.size() || d->error != DecodeError::none ? *d
                                                                    : Decoded{DecodeError::missing_etx, {}};
    }
  }
  return {DecodeError::wrong_length, {}};
}

std::optional<Decoded> FrameDecoder::push(std::uint8_t byte) noexcept {
  if (!in_frame_) {
    if (byte == kStx) {
      in_frame_ = true;
      size_ = expected_size_ = 0;
    } else {
      ++skipped_;
    }
    return std::nullopt;
  }
  if (byte == kStx) {
    // Resynchronise on the new STX: the cut-off frame is reported, the new one is collected.
    size_ = expected_size_ = 0;
    return Decoded{DecodeError::interrupted, {}};
  }
  if (byte == kEtx) {
    if (expected_size_ == 0 || size_ != expected_size_) return fail(DecodeError::wrong_length);
    in_frame_ = false;
    return finish();
  }
  if (size_ == expected_size_ && expected_size_ != 0) return fail(DecodeError::missing_etx);
  if (wire_hex_value(byte) < 0) return fail(DecodeError::bad_hex_digit);
  text_[size_++] = byte;
  return size_ == kHeaderTextLength ? check_header() : std::nullopt;
}

void FrameDecoder::reset() noexcept {
  in_frame_ = false;
  size_ = expected_size_ = 0;
}

std::optional<Decoded> FrameDecoder::fail(DecodeError e) noexcept {
  reset();
  return Decoded{e, {}};
}

std::optional<Decoded> FrameDecoder::check_header() noexcept {
  const std::span<const std::uint8_t> text(text_);
  if (byte_at(text, 0) != kVersion) return fail(DecodeError::bad_version);
  const int expected_length = data_length(byte_at(text, 2));
  if (expected_length < 0) return fail(DecodeError::unknown_message);
  if (byte_at(text, 4) != expected_length) return fail(DecodeError::wrong_length);
  expected_size_ = kHeaderTextLength + 2 * static_cast<std::size_t>(expected_length) + 2;
  return std::nullopt;
}

Decoded FrameDecoder::finish() const noexcept {
  const std::span<const std::uint8_t> text(text_.data(), size_);
  if (Codec::checksum(text.first(size_ - 2)) != byte_at(text, size_ - 2))
    return {DecodeError::bad_checksum, {}};
  std::array<std::uint8_t, kMaxDataLength> data{};
  const std::size_t n = (size_ - kHeaderTextLength - 2) / 2;
  for (std::size_t i = 0; i < n; ++i) data[i] = byte_at(text, kHeaderTextLength + 2 * i);
  return Codec::decode_data(byte_at(text, 2), std::span(data).first(n));
}

}  // namespace cellctl::spindle

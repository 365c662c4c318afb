#include "scu/codec.hpp"

#include "scu/crc16.hpp"
#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::scu {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
// Written out for clang 14 (the fuzz preset), which does not yet deduce aggregates' arguments.
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

// Appends the CRC of everything written so far and publishes the telegram into `out`.
template <std::size_t N>
bool seal(wire::ByteWriter& w, wire::FixedBytes<N>& out) noexcept {
  const auto crc = crc16(w.written());
  w.le(crc);
  if (!w.ok()) {
    out.clear();
    return false;
  }
  out.resize(w.size());
  return true;
}

constexpr std::size_t kCrcSize = 2;

}  // namespace

Command command_of(const Request& r) noexcept {
  return std::visit(Overloaded{
                        [](const OpenRequest&) { return Command::open; },
                        [](const AbortRequest&) { return Command::abort; },
                        [](const CyclicRequest&) { return Command::cyclic; },
                        [](const GetRequest&) { return Command::get; },
                        [](const TransferRequest&) { return Command::transfer; },
                        [](const ExecuteRequest&) { return Command::execute; },
                        [](const StopRequest&) { return Command::stop; },
                    },
                    r);
}

ReplyShape reply_shape(const Request& r) noexcept {
  const Command c = command_of(r);
  bool data = c == Command::get;
  if (const auto* rc = std::get_if<CyclicRequest>(&r)) data = rc->index != kNoCyclicObject;
  return {c, data};
}

const char* to_string(DecodeError e) noexcept {
  switch (e) {
    case DecodeError::none:
      return "no error";
    case DecodeError::bad_start:
      return "garbage (no 'R' at the start)";
    case DecodeError::unknown_command:
      return "unknown command byte";
    case DecodeError::unexpected_command:
      return "reply to another command than the one in flight";
    case DecodeError::bad_status:
      return "invalid status byte";
    case DecodeError::bad_length:
      return "impossible length";
    case DecodeError::bad_crc:
      return "CRC mismatch";
  }
  return "?";
}

bool crc_ok(std::span<const std::uint8_t> frame) noexcept {
  if (frame.size() < kCrcSize) return false;
  const auto body = frame.first(frame.size() - kCrcSize);
  const auto got = wire::ByteReader(frame.last(kCrcSize)).le<std::uint16_t>();
  return crc16(body) == got;
}

bool encode_request(const Request& r, RequestBytes& out) noexcept {
  wire::ByteWriter w(out.storage());
  w.u8(kMajor);
  w.u8(static_cast<std::uint8_t>(command_of(r)));
  const bool fits = std::visit(Overloaded{
                                   [&](const OpenRequest& o) {
                                     w.u8(o.safety_id);
                                     return true;
                                   },
                                   [&](const AbortRequest&) { return true; },
                                   [&](const CyclicRequest& c) {
                                     if (c.write_data.size() + 1 > kMaxRequestData) return false;
                                     w.le(static_cast<std::uint16_t>(1 + c.write_data.size()));
                                     w.u8(c.index);
                                     w.bytes(c.write_data);
                                     return true;
                                   },
                                   [&](const GetRequest& g) {
                                     w.le(g.data_id);
                                     return true;
                                   },
                                   [&](const TransferRequest& t) {
                                     if (t.value.size() + 2 > kMaxRequestData) return false;
                                     w.le(static_cast<std::uint16_t>(2 + t.value.size()));
                                     w.le(t.data_id);
                                     w.bytes(t.value);
                                     return true;
                                   },
                                   [&](const ExecuteRequest& e) {
                                     w.u8(e.function);
                                     w.u8(e.direction);
                                     w.u8(e.start_stop);
                                     return true;
                                   },
                                   [&](const StopRequest& s) {
                                     w.u8(s.function);
                                     w.u8(s.mode);
                                     return true;
                                   },
                               },
                               r);
  if (!fits) {
    out.clear();
    return false;
  }
  return seal(w, out);
}

bool encode_reply(const Reply& r, ReplyBytes& out) noexcept {
  wire::ByteWriter w(out.storage());
  w.u8(kMajor);
  w.u8(static_cast<std::uint8_t>(r.command));
  w.u8(static_cast<std::uint8_t>(r.status));
  // An error reply never carries data, whatever the request was.
  if (r.status == Status::ack && r.has_data) {
    if (r.data.size() > kMaxReplyData) {
      out.clear();
      return false;
    }
    w.le(static_cast<std::uint16_t>(r.data.size()));
    w.bytes(r.data);
  }
  return seal(w, out);
}

FrameLength request_frame_length(std::span<const std::uint8_t> prefix) noexcept {
  if (prefix.empty()) return {};
  if (prefix[0] != kMajor) return {0, DecodeError::bad_start};
  if (prefix.size() < 2) return {};
  const auto cmd = command_from_byte(prefix[1]);
  if (!cmd) return {0, DecodeError::unknown_command};
  switch (*cmd) {
    case Command::abort:
      return {4};
    case Command::open:
      return {5};
    case Command::get:
    case Command::stop:
      return {6};
    case Command::execute:
      return {7};
    case Command::transfer:
    case Command::cyclic: {
      if (prefix.size() < 4) return {};
      const std::size_t ctp = wire::ByteReader(prefix.subspan(2, 2)).le<std::uint16_t>();
      if (ctp > kMaxRequestData) return {0, DecodeError::bad_length};
      return {4 + ctp + kCrcSize};
    }
  }
  return {0, DecodeError::unknown_command};
}

FrameLength reply_frame_length(std::span<const std::uint8_t> prefix, ReplyShape expected) noexcept {
  if (prefix.empty()) return {};
  if (prefix[0] != kMajor) return {0, DecodeError::bad_start};
  if (prefix.size() < 2) return {};
  if (!command_from_byte(prefix[1])) return {0, DecodeError::unknown_command};
  if (prefix[1] != static_cast<std::uint8_t>(expected.command)) return {0, DecodeError::unexpected_command};
  if (prefix.size() < 3) return {};
  const auto status = status_from_byte(prefix[2]);
  if (!status) return {0, DecodeError::bad_status};
  if (*status != Status::ack || !expected.has_data) return {5};
  if (prefix.size() < 5) return {};
  const std::size_t ctp = wire::ByteReader(prefix.subspan(3, 2)).le<std::uint16_t>();
  if (ctp > kMaxReplyData) return {0, DecodeError::bad_length};
  return {5 + ctp + kCrcSize};
}

Decoded<Request> decode_request(std::span<const std::uint8_t> frame) noexcept {
  const auto len = request_frame_length(frame);
  if (len.error != DecodeError::none) return {{}, len.error};
  if (len.length == 0 || len.length != frame.size()) return {{}, DecodeError::bad_length};
  if (!crc_ok(frame)) return {{}, DecodeError::bad_crc};
  wire::ByteReader r(frame.first(frame.size() - kCrcSize));
  (void)r.u8();  // the major, checked with the length
  const auto cmd = *command_from_byte(r.u8());
  Request out;
  switch (cmd) {
    case Command::open:
      out = OpenRequest{r.u8()};
      break;
    case Command::abort:
      out = AbortRequest{};
      break;
    case Command::get:
      out = GetRequest{r.le<std::uint16_t>()};
      break;
    case Command::stop: {
      const auto f = r.u8();
      out = StopRequest{f, r.u8()};
      break;
    }
    case Command::execute: {
      const auto f = r.u8();
      const auto d = r.u8();
      out = ExecuteRequest{f, d, r.u8()};
      break;
    }
    case Command::cyclic: {
      const auto ctp = r.le<std::uint16_t>();
      if (ctp < 1) return {{}, DecodeError::bad_length};  // the index byte is mandatory
      const auto index = r.u8();
      out = CyclicRequest{index, r.rest()};
      break;
    }
    case Command::transfer: {
      const auto ctp = r.le<std::uint16_t>();
      if (ctp < 2) return {{}, DecodeError::bad_length};  // the data ID is mandatory
      const auto id = r.le<std::uint16_t>();
      out = TransferRequest{id, r.rest()};
      break;
    }
  }
  if (!r.ok()) return {{}, DecodeError::bad_length};
  return {out, DecodeError::none};
}

Decoded<Reply> decode_reply(std::span<const std::uint8_t> frame, ReplyShape expected) noexcept {
  const auto len = reply_frame_length(frame, expected);
  if (len.error != DecodeError::none) return {{}, len.error};
  if (len.length == 0 || len.length != frame.size()) return {{}, DecodeError::bad_length};
  if (!crc_ok(frame)) return {{}, DecodeError::bad_crc};
  Reply out;
  out.command = expected.command;
  out.status = *status_from_byte(frame[2]);
  if (out.status == Status::ack && expected.has_data) {
    out.has_data = true;
    out.data = frame.subspan(5, frame.size() - 5 - kCrcSize);
  }
  return {out, DecodeError::none};
}

}  // namespace cellctl::scu

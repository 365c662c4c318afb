// scu::Emulator: the telegrams in and out — requests read from the link and decoded, each answered
// (a damaged one with the manual's error status), replies queued and written as the line takes them —
// and the faults a test injects on this path: refused, lost, late and damaged replies.
#include <algorithm>
#include <variant>

#include "scu/emulator.hpp"

namespace cellctl::scu {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
// Written out for clang 14 (the fuzz preset), which does not yet deduce aggregates' arguments.
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace

void Emulator::receive(link::TimePoint now) {
  // A request's length at a time: beside the part of a request it may hold, the stream (two requests)
  // takes all of it, and the events are drained before the next read.
  std::array<std::uint8_t, kMaxRequestTelegram> buf{};
  if (requests_.expire(now) > 0) ++discarded_partials_;
  for (;;) {
    const auto r = link_.read(buf);
    if (!r.ok() || r.count == 0) break;
    (void)requests_.feed(std::span(buf).first(r.count), now);  // all of it (see buf)
    for (auto e = requests_.next(); e.kind != RequestStream::Event::Kind::need_more; e = requests_.next()) {
      if (e.kind == RequestStream::Event::Kind::request) {
        answer(e.request, now);
        continue;
      }
      switch (e.error) {
        case DecodeError::bad_crc:
          answer_error(e.command_byte, Status::checksum_error, now);
          break;
        case DecodeError::bad_length:
          answer_error(e.command_byte, Status::parameter_count_error, now);
          break;
        case DecodeError::unknown_command:
          answer_error(e.command_byte, Status::invalid_command, now);
          break;
        default:
          break;  // garbage before a telegram gets no answer: there is nobody to answer
      }
    }
  }
}

void Emulator::answer(const Request& request, link::TimePoint now) {
  if (refuse_count_ > 0 && (!refuse_only_ || *refuse_only_ == command_of(request))) {
    --refuse_count_;
    send(Reply{command_of(request), refuse_status_, false, {}}, now);
    return;
  }
  wire::ByteWriter data(reply_data_);
  Reply reply;
  reply.command = command_of(request);
  reply.has_data = reply_shape(request).has_data;
  reply.status = std::visit(Overloaded{
                                [&](const OpenRequest& r) { return handle(r, now); },
                                [&](const AbortRequest& r) { return handle(r, now); },
                                [&](const CyclicRequest& r) { return handle(r, now, data); },
                                [&](const GetRequest& r) { return handle(r, data); },
                                [&](const TransferRequest& r) { return handle(r); },
                                [&](const ExecuteRequest& r) { return handle(r); },
                                [&](const StopRequest& r) { return handle(r); },
                            },
                            request);
  reply.data = data.written();
  send(reply, now);
}

void Emulator::answer_error(std::uint8_t command_byte, Status s, link::TimePoint now) {
  send(Reply{static_cast<Command>(command_byte), s, false, {}}, now);
}

void Emulator::send(const Reply& reply, link::TimePoint now) {
  ++answered_;
  if (drop_replies_ > 0) {
    --drop_replies_;
    return;
  }
  if (outgoing_count_ == kOutgoing) return;  // a master that does not wait for replies loses some
  auto& slot = outgoing_[outgoing_count_];
  if (!encode_reply(reply, slot.bytes)) return;
  if (corrupt_next_) {
    corrupt_next_ = false;
    auto bytes = slot.bytes.storage();
    bytes[slot.bytes.size() - 1] ^= 0x5A;
  }
  slot.due = now + reply_delay_;
  ++outgoing_count_;
}

void Emulator::flush(link::TimePoint now) {
  while (outgoing_count_ > 0 && outgoing_[0].due <= now) {
    const auto bytes = outgoing_[0].bytes.view();
    if (bytes.size() > tx_.size() - tx_size_) break;
    std::copy(bytes.begin(), bytes.end(), tx_.begin() + static_cast<std::ptrdiff_t>(tx_size_));
    tx_size_ += bytes.size();
    std::move(outgoing_.begin() + 1, outgoing_.begin() + static_cast<std::ptrdiff_t>(outgoing_count_),
              outgoing_.begin());
    --outgoing_count_;
  }
  if (tx_size_ == 0) return;
  const auto r = link_.write(std::span(tx_).first(tx_size_));
  if (!r.ok() || r.count == 0) return;
  std::copy(tx_.begin() + static_cast<std::ptrdiff_t>(r.count),
            tx_.begin() + static_cast<std::ptrdiff_t>(tx_size_), tx_.begin());
  tx_size_ -= r.count;
}

}  // namespace cellctl::scu

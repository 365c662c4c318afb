#include "link/fault_injecting_link.hpp"

#include <algorithm>
#include <cerrno>

namespace cellctl::link {
namespace {

// Garbage comes in bursts of 1..kMaxBurst random bytes, kMinGap..kMaxGap apart: line noise that
// hits some telegrams and spares others.
constexpr std::uint32_t kMaxBurst = 6;
constexpr std::uint32_t kMinGapMs = 3;
constexpr std::uint32_t kMaxGapMs = 12;

IoResult port_gone() noexcept {
  return {0, IoStatus::closed, EIO};
}

}  // namespace

FaultInjectingLink::FaultInjectingLink(Link& inner, const Clock& clock, std::uint32_t seed) noexcept
    : inner_(inner), clock_(clock), rng_(seed == 0 ? 1 : seed) {}

bool FaultInjectingLink::schedule(LinkFault fault, TimePoint from, std::optional<TimePoint> until) noexcept {
  if (window_count_ == kMaxWindows) return false;
  windows_[window_count_++] = Window{fault, from, until};
  return true;
}

std::optional<LinkFault> FaultInjectingLink::active(TimePoint now) const noexcept {
  for (std::size_t i = 0; i < window_count_; ++i) {
    const auto& w = windows_[i];
    if (now >= w.from && (!w.until || now < *w.until)) return w.fault;
  }
  return std::nullopt;
}

IoResult FaultInjectingLink::read(std::span<std::uint8_t> buffer) {
  const TimePoint now = clock_.now();
  const auto fault = active(now);
  const auto acting = [&fault](LinkFaultKind k) { return fault && fault->kind == k; };
  if (acting(LinkFaultKind::silent) || acting(LinkFaultKind::disconnect)) {
    counters_.lost += delayed_.size();
    delayed_.clear();
    const auto r = discard_inbound();
    if (!r.ok()) return r;
    return acting(LinkFaultKind::silent) ? IoResult{} : port_gone();
  }
  const std::size_t injected = acting(LinkFaultKind::garbage) ? garbage(buffer, inbound_, now) : 0;
  const auto rest = buffer.subspan(injected);
  std::size_t n = 0;
  if (acting(LinkFaultKind::delay) || delayed_.size() > 0) {
    // Replies held back by a delay that has ended still come first, in order: newer bytes queue behind.
    const bool delaying = acting(LinkFaultKind::delay);
    const auto r = hold_inbound(delaying ? now + fault->delay : now, delaying);
    if (!r.ok()) return r;
    n = delayed_.pop_due(rest, now);
  } else {
    const auto r = inner_.read(rest);
    if (!r.ok()) return r;
    n = r.count;
  }
  if (acting(LinkFaultKind::corrupt)) corrupt(rest.first(n), inbound_);
  return {injected + n};
}

IoResult FaultInjectingLink::write(std::span<const std::uint8_t> bytes) {
  const TimePoint now = clock_.now();
  const auto fault = active(now);
  if (!fault || fault->kind == LinkFaultKind::delay) return inner_.write(bytes);  // delay: replies only
  switch (fault->kind) {
    case LinkFaultKind::silent:
      counters_.lost += bytes.size();
      return {bytes.size()};  // taken, into a line that carries nothing
    case LinkFaultKind::disconnect:
      counters_.lost += bytes.size();
      return port_gone();
    case LinkFaultKind::garbage: {
      const std::size_t g = garbage(scratch_, outbound_, now);
      if (g > 0) (void)inner_.write(std::span(scratch_).first(g));  // noise the line could not carry is lost
      return inner_.write(bytes);
    }
    case LinkFaultKind::corrupt: {
      const std::size_t n = std::min(bytes.size(), scratch_.size());
      std::copy_n(bytes.begin(), n, scratch_.begin());
      corrupt(std::span(scratch_).first(n), outbound_);
      return inner_.write(std::span(scratch_).first(n));
    }
    case LinkFaultKind::delay:
      break;
  }
  return inner_.write(bytes);
}

IoResult FaultInjectingLink::reopen() {
  const auto fault = active(clock_.now());
  if (fault && fault->kind == LinkFaultKind::disconnect) return port_gone();
  return inner_.reopen();
}

IoResult FaultInjectingLink::discard_inbound() {
  for (;;) {
    const auto r = inner_.read(scratch_);
    if (!r.ok() || r.count == 0) return r.ok() ? IoResult{} : r;
    counters_.lost += r.count;
  }
}

IoResult FaultInjectingLink::hold_inbound(TimePoint due, bool delaying) {
  while (!delayed_.full()) {
    const std::size_t room = std::min(scratch_.size(), delayed_.capacity() - delayed_.size());
    const auto r = inner_.read(std::span(scratch_).first(room));
    if (!r.ok()) return r;
    if (r.count == 0) break;
    for (std::size_t i = 0; i < r.count; ++i) (void)delayed_.push(scratch_[i], due);  // room: read no more
    if (delaying) counters_.delayed += r.count;
  }
  return {};
}

void FaultInjectingLink::corrupt(std::span<std::uint8_t> bytes, Direction& d) noexcept {
  for (auto& b : bytes) {
    if (d.corrupt_phase == 0) {
      b = static_cast<std::uint8_t>(b ^ (1u << (rng_() % 8)));
      ++counters_.flipped;
    }
    d.corrupt_phase = (d.corrupt_phase + 1) % kCorruptStride;
  }
}

std::size_t FaultInjectingLink::garbage(std::span<std::uint8_t> out, Direction& d, TimePoint now) noexcept {
  if (now < d.next_garbage || out.empty()) return 0;
  const std::size_t n = std::min<std::size_t>(out.size(), 1 + rng_() % kMaxBurst);
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>(rng_() >> 8);
  d.next_garbage = now + std::chrono::milliseconds(kMinGapMs + rng_() % (kMaxGapMs - kMinGapMs + 1));
  counters_.injected += n;
  return n;
}

}  // namespace cellctl::link

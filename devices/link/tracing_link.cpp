#include "link/tracing_link.hpp"

#include <fmt/chrono.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "wire/hex.hpp"

namespace cellctl::link {

LogTraceSink::LogTraceSink(wire::WhenFull when_full, Writer writer)
    : when_full_(when_full), queue_(std::make_unique<wire::SpscQueue<TraceRecord, 512>>()) {
  if (writer == Writer::thread) writer_ = std::thread([this] { write_loop(); });
}

LogTraceSink::~LogTraceSink() {
  stop_.store(true, std::memory_order_release);
  if (writer_.joinable()) writer_.join();
  drain();
}

void LogTraceSink::record(TimePoint at, std::string_view link, Direction dir,
                          std::span<const std::uint8_t> bytes) noexcept {
  TraceRecord r;
  r.at = at;
  r.dir = dir;
  r.link_size = static_cast<std::uint8_t>(std::min(link.size(), r.link.size()));
  std::copy_n(link.begin(), r.link_size, r.link.begin());
  do {
    const auto piece = bytes.first(std::min(bytes.size(), TraceRecord::kMaxBytes));
    r.bytes.assign(piece);
    while (!queue_->push(r)) {
      if (when_full_ == wire::WhenFull::drop_and_count) {
        dropped_.fetch_add(1, std::memory_order_relaxed);
        break;
      }
      std::this_thread::yield();
    }
    bytes = bytes.subspan(piece.size());
  } while (!bytes.empty());
}

void LogTraceSink::start_clock(TimePoint run_start) noexcept {
  epoch_ = run_start;
  wall_epoch_ = std::chrono::system_clock::now();
  epoch_set_.store(true, std::memory_order_release);
}

std::size_t LogTraceSink::drain() {
  const auto logger = spdlog::get("trace");
  std::size_t n = 0;
  while (const auto r = queue_->pop()) {
    ++n;
    if (!epoch_set_.load(std::memory_order_acquire)) start_clock(r->at);  // no run: from the first telegram
    const auto since = r->at - epoch_;
    const auto wall = std::chrono::floor<std::chrono::microseconds>(
        wall_epoch_ + std::chrono::duration_cast<std::chrono::system_clock::duration>(since));
    const auto micros = (wall.time_since_epoch() % std::chrono::seconds(1)).count();
    if (logger)
      logger->info("{:11.6f} s {:%H:%M:%S}.{:06} {} {} {}", to_seconds(since),
                   fmt::localtime(std::chrono::system_clock::to_time_t(wall)), micros,
                   std::string_view(r->link.data(), r->link_size), r->dir == Direction::tx ? "TX" : "RX",
                   wire::to_hex(r->bytes.view()));
  }
  const auto dropped = dropped_.load(std::memory_order_relaxed);
  if (dropped != reported_drops_ && logger)
    logger->warn("{} trace records dropped: the writer fell behind the links", dropped - reported_drops_);
  reported_drops_ = dropped;
  return n;
}

void LogTraceSink::write_loop() {
  // Polled rather than woken: a notify from record() could take a lock on the cycle's thread.
  while (!stop_.load(std::memory_order_acquire))
    if (drain() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

IoResult TracingLink::read(std::span<std::uint8_t> buffer) {
  IoResult r = inner_.read(buffer);
  if (r.count == 0) {
    flush_rx();  // a quiet poll ends the received run
    return r;
  }
  if (rx_.empty()) rx_started_ = clock_.now();
  for (std::size_t i = 0; i < r.count; ++i) {
    if (!rx_.push_back(buffer[i])) {
      flush_rx();
      rx_started_ = clock_.now();
      rx_.push_back(buffer[i]);
    }
  }
  return r;
}

IoResult TracingLink::write(std::span<const std::uint8_t> bytes) {
  flush_rx();
  IoResult r = inner_.write(bytes);
  if (r.count > 0) sink_.record(clock_.now(), name_, Direction::tx, bytes.first(r.count));
  return r;
}

void TracingLink::flush_rx() {
  if (rx_.empty()) return;
  sink_.record(rx_started_, name_, Direction::rx, rx_.view());
  rx_.clear();
}

}  // namespace cellctl::link

#include "link/tracing_link.hpp"

#include <spdlog/spdlog.h>

#include "wire/hex.hpp"

namespace cellctl::link {

void LogTraceSink::record(TimePoint at, std::string_view link, Direction dir,
                          std::span<const std::uint8_t> bytes) {
  auto logger = spdlog::get("trace");
  if (!logger) return;
  logger->info("{:12.6f} {} {} {}", to_seconds(at.time_since_epoch()), link,
               dir == Direction::tx ? "TX" : "RX", wire::to_hex(bytes));
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

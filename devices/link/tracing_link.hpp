#pragma once
// A hex trace of the telegrams crossing a link, with timestamps: wraps any Link, passes every byte
// through unchanged and reports each write as one TX record and each run of received bytes (ended
// by a quiet poll or by the next write) as one RX record. Switched on per link from the CLI.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "link/clock.hpp"
#include "link/link.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::link {

enum class Direction : std::uint8_t { tx, rx };

class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void record(TimePoint at, std::string_view link, Direction dir,
                      std::span<const std::uint8_t> bytes) = 0;
};

// Writes "  12.345678 scu TX 52 4f 00 5c 2d" lines to the spdlog logger named "trace" (created
// asynchronous by the CLI, so formatting and output happen off the control cycle's thread).
class LogTraceSink final : public TraceSink {
 public:
  void record(TimePoint at, std::string_view link, Direction dir,
              std::span<const std::uint8_t> bytes) override;
};

class TracingLink final : public Link {
 public:
  TracingLink(Link& inner, const Clock& clock, TraceSink& sink, std::string name)
      : inner_(inner), clock_(clock), sink_(sink), name_(std::move(name)) {}

  IoResult read(std::span<std::uint8_t> buffer) override;
  IoResult write(std::span<const std::uint8_t> bytes) override;
  [[nodiscard]] std::string describe() const override { return inner_.describe(); }

 private:
  void flush_rx();

  Link& inner_;
  const Clock& clock_;
  TraceSink& sink_;
  std::string name_;
  wire::FixedBytes<512> rx_;
  TimePoint rx_started_{};
};

}  // namespace cellctl::link

#pragma once
// An in-memory serial line between two endpoints, "master" (the session's side) and "device" (the
// emulator's side). Each direction is a wire of its own: a byte written at t is readable at the
// other end once the line is free and one character time has passed, so telegram timing, reply
// latency and throughput limits are those of the real baud rate and framing — on the injected clock.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "link/clock.hpp"
#include "link/line_format.hpp"
#include "link/link.hpp"
#include "link/timed_byte_queue.hpp"

namespace cellctl::link {

class SimLink {
 public:
  SimLink(const Clock& clock, LineFormat format, std::string name = "sim");
  SimLink(const SimLink&) = delete;
  SimLink& operator=(const SimLink&) = delete;

  [[nodiscard]] Link& master() noexcept { return master_end_; }
  [[nodiscard]] Link& device() noexcept { return device_end_; }
  [[nodiscard]] const LineFormat& format() const noexcept { return format_; }

  // A cut cable: while cut, bytes written in either direction are lost.
  void set_cut(bool cut) noexcept { cut_ = cut; }

  // The earliest time at which a byte still on the wire becomes readable, in either direction; lets a
  // virtual-time driver jump straight to the next event instead of stepping blindly.
  [[nodiscard]] std::optional<TimePoint> next_delivery() const noexcept;

 private:
  // One direction of the line: bytes with the time they finish arriving.
  class Wire {
   public:
    std::size_t send(std::span<const std::uint8_t> bytes, TimePoint now, Duration char_time) noexcept;
    std::size_t receive(std::span<std::uint8_t> out, TimePoint now) noexcept {
      return bytes_.pop_due(out, now);
    }
    [[nodiscard]] std::optional<TimePoint> next_delivery() const noexcept { return bytes_.next_due(); }

   private:
    TimedByteQueue<4096> bytes_;  // like a UART FIFO plus driver buffer
    TimePoint line_free_at_{};
  };

  class End final : public Link {
   public:
    End(SimLink& owner, Wire& out, Wire& in, std::string name)
        : owner_(owner), out_(out), in_(in), name_(std::move(name)) {}
    IoResult read(std::span<std::uint8_t> buffer) override;
    IoResult write(std::span<const std::uint8_t> bytes) override;
    [[nodiscard]] std::string describe() const override { return name_; }

   private:
    SimLink& owner_;
    Wire& out_;
    Wire& in_;
    std::string name_;
  };

  const Clock& clock_;
  LineFormat format_;
  bool cut_ = false;
  Wire to_device_;
  Wire to_master_;
  End master_end_;
  End device_end_;
};

}  // namespace cellctl::link

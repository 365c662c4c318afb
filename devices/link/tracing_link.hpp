#pragma once
// A hex trace of the telegrams crossing a link, with timestamps: wraps any Link, passes every byte
// through unchanged and reports each write as one TX record and each run of received bytes (ended
// by a quiet poll or by the next write) as one RX record. Switched on per link from the CLI.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <thread>

#include "link/clock.hpp"
#include "link/link.hpp"
#include "wire/fixed_bytes.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::link {

enum class Direction : std::uint8_t { tx, rx };

class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void record(TimePoint at, std::string_view link, Direction dir,
                      std::span<const std::uint8_t> bytes) = 0;
};

// One record as it crosses from the cycle's thread to the trace writer: fixed size, no pointers.
struct TraceRecord {
  static constexpr std::size_t kMaxBytes = 256;  // a longer run is split into several records
  TimePoint at{};
  Direction dir = Direction::tx;
  std::array<char, 24> link{};  // the link's name, cut to fit
  std::uint8_t link_size = 0;
  wire::FixedBytes<kMaxBytes> bytes;
};

// Writes "   0.512345 s 09:12:03.456789 scu TX 52 4f 00 5c 2d" lines — seconds of the run (the time a
// run's journal uses) and the wall-clock time of the telegram — to the spdlog logger named "trace",
// but never on
// the caller's thread: record() copies into a lock-free ring (no lock, no allocation — it runs in the
// control cycle) and a writer thread formats and logs. Every TracingLink sharing one sink must call it
// from the same thread (single producer). A full ring drops the record and counts it (the writer
// reports the count), or — WhenFull::wait, for virtual time — waits for the writer.
class LogTraceSink final : public TraceSink {
 public:
  enum class Writer : std::uint8_t { thread, manual };  // manual: nothing is written until drain()
  // WhenFull::wait needs Writer::thread (a manual sink would wait for itself).
  explicit LogTraceSink(wire::WhenFull when_full = wire::WhenFull::drop_and_count,
                        Writer writer = Writer::thread);
  ~LogTraceSink() override;  // stops the writer, then writes what is left
  LogTraceSink(const LogTraceSink&) = delete;
  LogTraceSink& operator=(const LogTraceSink&) = delete;

  void record(TimePoint at, std::string_view link, Direction dir,
              std::span<const std::uint8_t> bytes) noexcept override;
  // The run started at `run_start` on the links' clock, now on the wall clock: trace times count from
  // there. Without it they count from the first telegram. Before the first record is written.
  void start_clock(TimePoint run_start) noexcept;
  // Formats and logs every queued record; returns how many. The consumer side: the writer thread's,
  // or the caller's with Writer::manual.
  std::size_t drain();
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  void write_loop();

  wire::WhenFull when_full_;
  std::unique_ptr<wire::SpscQueue<TraceRecord, 512>> queue_;
  std::atomic<std::uint64_t> dropped_{0};
  std::uint64_t reported_drops_ = 0;  // writer side
  std::atomic<bool> epoch_set_{false};
  TimePoint epoch_{};                                   // written before epoch_set_ is released
  std::chrono::system_clock::time_point wall_epoch_{};  // the wall clock at epoch_
  std::atomic<bool> stop_{false};
  std::thread writer_;
};

class TracingLink final : public Link {
 public:
  TracingLink(Link& inner, const Clock& clock, TraceSink& sink, std::string name)
      : inner_(inner), clock_(clock), sink_(sink), name_(std::move(name)) {}

  IoResult read(std::span<std::uint8_t> buffer) override;
  IoResult write(std::span<const std::uint8_t> bytes) override;
  [[nodiscard]] std::string describe() const override { return inner_.describe(); }
  void arm_crash_stop(std::span<const std::uint8_t> telegram) noexcept override {
    inner_.arm_crash_stop(telegram);
  }
  IoResult reopen() override { return inner_.reopen(); }

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

#pragma once
// The run record: a JSON-lines file of every state change, step, command, fault and a periodic
// sample. The control cycle only posts fixed-size events into a lock-free queue; a writer thread
// formats, writes and flushes them, so nothing is lost on a fault or Ctrl-C and the cycle never
// waits on a disk. At the end it adds the summary and draws the plots (plot.svg, plot.html).

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "journal/event.hpp"
#include "journal/event_sink.hpp"
#include "journal/run_summary.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::journal {

// What post() does when the writer has fallen behind (wire/spsc_queue.hpp): dropped and counted in the
// summary, or waited for in virtual time.
using WhenFull = wire::WhenFull;

class Journal final : public EventSink {
 public:
  // Creates `dir` if needed, opens dir/journal.jsonl and writes `header` (record_header.hpp) as its
  // first line unless it is null; throws std::runtime_error naming the path.
  Journal(const std::filesystem::path& dir, WhenFull when_full, const nlohmann::json& header = {});
  ~Journal() override;
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Cycle side: no allocation, no lock, no I/O.
  void post(double t, const Payload& payload) noexcept override;

  // Drains everything, appends {"event":"summary",…} with `extra` merged in (cycle statistics),
  // writes plot.svg and plot.html, flushes and closes. Idempotent.
  void close(const nlohmann::json& extra = {});

  // Called on the writer thread with every line as it is written (the terminal answers typed
  // commands and reports faults from what the run records). Never on the cycle's thread.
  void on_line(std::function<void(const nlohmann::json&)> listener);

  [[nodiscard]] const std::filesystem::path& dir() const noexcept { return dir_; }
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(); }
  // Valid after close().
  [[nodiscard]] const RunSummary& summary() const noexcept { return summary_; }

 private:
  void run_writer();
  bool drain();

  std::filesystem::path dir_;
  WhenFull when_full_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<wire::SpscQueue<Event, 8192>> queue_;
  std::atomic<bool> closing_{false};
  std::atomic<std::uint64_t> dropped_{0};
  RunSummary summary_;         // writer thread only until close()
  std::string note_parts_;     // writer thread: a long note's parts so far
  std::mutex listener_mutex_;  // writer thread and the thread setting it; the cycle never takes it
  std::function<void(const nlohmann::json&)> listener_;
  std::thread writer_;
  bool closed_ = false;
};

}  // namespace cellctl::journal

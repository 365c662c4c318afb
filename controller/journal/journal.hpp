#pragma once
// The run record: a JSON-lines file of every state change, step, command, fault and a periodic
// sample. The control cycle only posts fixed-size events into a lock-free queue; a writer thread
// writes them (their lines made by the schema, schema/journal_line.hpp) and flushes them, so nothing
// is lost on a fault or Ctrl-C and the cycle never waits on a disk, and hands each, typed, to the
// run's listener (event_listener.hpp). At the end it adds the summary and draws the plots (plot.svg,
// plot.html).

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "journal/event.hpp"
#include "journal/event_listener.hpp"
#include "journal/event_sink.hpp"
#include "journal/run_summary.hpp"
#include "schema/record_header.hpp"
#include "schema/summary_line.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::journal {

// What post() does when the writer has fallen behind (wire/spsc_queue.hpp): dropped and counted in the
// summary, or waited for in virtual time.
using WhenFull = wire::WhenFull;

class Journal final : public EventSink {
 public:
  // Creates `dir` if needed, opens dir/journal.jsonl and writes `header` (record_header.hpp) as its
  // first line when there is one; throws std::runtime_error naming the path.
  Journal(const std::filesystem::path& dir, WhenFull when_full,
          const std::optional<schema::RecordHeader>& header = std::nullopt);
  ~Journal() override;
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Cycle side: no allocation, no lock, no I/O.
  void post(double t, const Payload& payload) noexcept override;

  // Drains everything, appends the summary line with what the run adds to it (its loop, links, safe
  // states: `run`), writes plot.svg and plot.html, flushes and closes. Idempotent.
  void close(const std::optional<schema::RunFigures>& run = std::nullopt);
  // The same for a run that never started: its summary says why.
  void close_not_started(const std::string& reason);

  // Hears every event as it is written, on the writer thread, never on the cycle's (the terminal
  // answers typed commands and reports faults from what the run records; the plant link and the page
  // follow the run). nullptr: nobody. The listener must outlive the journal or be taken away first.
  void listen(EventListener* listener);

  [[nodiscard]] const std::filesystem::path& dir() const noexcept { return dir_; }
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(); }
  // Valid after close().
  [[nodiscard]] const RunSummary& summary() const noexcept { return summary_; }

 private:
  void run_writer();
  bool drain();
  void write_line(const std::string& line);
  // Drains what is left and ends the writer: the summary line's own part, the journal's figure added.
  schema::SummaryLine summary_line_after_drain();
  void finish(schema::SummaryLine line);

  std::filesystem::path dir_;
  WhenFull when_full_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<wire::SpscQueue<Event, 8192>> queue_;
  std::atomic<bool> closing_{false};
  std::atomic<std::uint64_t> dropped_{0};
  RunSummary summary_;         // writer thread only until close()
  std::string note_parts_;     // writer thread: a long note's parts so far
  std::mutex listener_mutex_;  // writer thread and the thread setting it; the cycle never takes it
  EventListener* listener_ = nullptr;
  std::thread writer_;
  bool closed_ = false;
};

}  // namespace cellctl::journal

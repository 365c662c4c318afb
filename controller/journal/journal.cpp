#include "journal/journal.hpp"

#include <fmt/format.h>

#include <chrono>
#include <fstream>
#include <stdexcept>

#include "journal/plot_html.hpp"
#include "journal/plot_svg.hpp"
#include "schema/journal_line.hpp"

namespace cellctl::journal {

Journal::Journal(const std::filesystem::path& dir, WhenFull when_full,
                 const std::optional<schema::RecordHeader>& header)
    : dir_(dir), when_full_(when_full), queue_(std::make_unique<wire::SpscQueue<Event, 8192>>()) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const auto path = dir_ / "journal.jsonl";
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr)
    throw std::runtime_error(fmt::format("cannot write the run record {}", path.string()));
  if (header) {
    summary_.record().set_header(*header);
    write_line(schema::header_line(*header));
    std::fflush(file_);
  }
  writer_ = std::thread([this] { run_writer(); });
}

Journal::~Journal() {
  close();
}

void Journal::post(double t, const Payload& payload) noexcept {
  const Event e{t, payload};
  while (!queue_->push(e)) {
    if (when_full_ == WhenFull::drop_and_count) {
      dropped_.fetch_add(1);
      return;
    }
    std::this_thread::yield();
  }
}

bool Journal::drain() {
  bool any = false;
  while (auto e = queue_->pop()) {
    any = true;
    e->t = schema::recorded_time(e->t);  // every reader of the event sees what the line records
    // A long note comes in parts: it is written, recorded and told as one note, whole.
    if (const auto* note = std::get_if<Note>(&e->payload)) {
      note_parts_ += note->text.view();
      if (note->continued) continue;
      summary_.add_note(e->t, note_parts_);
      {
        const std::lock_guard lock(listener_mutex_);
        if (listener_) listener_->on_note(e->t, note_parts_);
      }
      write_line(schema::note_line(e->t, note_parts_));
      note_parts_.clear();
      continue;
    }
    summary_.add(*e);
    {
      const std::lock_guard lock(listener_mutex_);
      if (listener_) listener_->on_event(*e);
    }
    write_line(schema::event_line(*e));
  }
  // Flushed after every batch: what was posted is in the file within a few milliseconds.
  if (any) std::fflush(file_);
  return any;
}

void Journal::write_line(const std::string& line) {
  std::fputs(line.c_str(), file_);
  std::fputc('\n', file_);
}

void Journal::listen(EventListener* listener) {
  const std::lock_guard lock(listener_mutex_);
  listener_ = listener;
}

void Journal::run_writer() {
  while (!closing_.load()) {
    if (!drain()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  drain();
}

void Journal::close(const std::optional<schema::RunFigures>& run) {
  if (closed_) return;
  auto line = summary_line_after_drain();
  line.run = run;
  finish(std::move(line));
}

void Journal::close_not_started(const std::string& reason) {
  if (closed_) return;
  auto line = summary_line_after_drain();
  line.not_started = reason;
  finish(std::move(line));
}

schema::SummaryLine Journal::summary_line_after_drain() {
  closed_ = true;
  closing_.store(true);
  if (writer_.joinable()) writer_.join();
  summary_.record().finish();
  auto line = summary_.line();
  line.journal_dropped = dropped_.load();
  return line;
}

void Journal::finish(schema::SummaryLine line) {
  write_line(schema::summary_line(line));
  std::fclose(file_);
  file_ = nullptr;
  std::ofstream(dir_ / "plot.svg") << render_svg({&summary_.record()});
  std::ofstream(dir_ / "plot.html") << render_html({&summary_.record()});
}

}  // namespace cellctl::journal

#include "journal/journal.hpp"

#include <fmt/format.h>

#include <chrono>
#include <fstream>
#include <stdexcept>

#include "journal/event_json.hpp"
#include "journal/plot_html.hpp"
#include "journal/plot_svg.hpp"

namespace cellctl::journal {

Journal::Journal(const std::filesystem::path& dir, WhenFull when_full, const nlohmann::json& header)
    : dir_(dir), when_full_(when_full), queue_(std::make_unique<wire::SpscQueue<Event, 8192>>()) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const auto path = dir_ / "journal.jsonl";
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr)
    throw std::runtime_error(fmt::format("cannot write the run record {}", path.string()));
  if (!header.is_null()) {
    summary_.add(header);
    std::fputs((header.dump() + "\n").c_str(), file_);
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
    // A long note comes in parts: they are written as one line, whole.
    if (const auto* note = std::get_if<Note>(&e->payload)) {
      note_parts_ += note->text.view();
      if (note->continued) continue;
    }
    auto j = to_json(*e);
    if (std::holds_alternative<Note>(e->payload)) {
      j["text"] = note_parts_;
      note_parts_.clear();
    }
    summary_.add(j);
    const auto line = j.dump();
    {
      const std::lock_guard lock(listener_mutex_);
      if (listener_) listener_(j);
    }
    std::fputs(line.c_str(), file_);
    std::fputc('\n', file_);
  }
  // Flushed after every batch: what was posted is in the file within a few milliseconds.
  if (any) std::fflush(file_);
  return any;
}

void Journal::on_line(std::function<void(const nlohmann::json&)> listener) {
  const std::lock_guard lock(listener_mutex_);
  listener_ = std::move(listener);
}

void Journal::run_writer() {
  while (!closing_.load()) {
    if (!drain()) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  drain();
}

void Journal::close(const nlohmann::json& extra) {
  if (closed_) return;
  closed_ = true;
  closing_.store(true);
  if (writer_.joinable()) writer_.join();
  summary_.record().finish();
  auto j = summary_.to_json();
  j["event"] = "summary";
  j["journal_dropped"] = dropped_.load();
  for (const auto& [k, v] : extra.items()) j[k] = v;
  const auto line = j.dump();
  std::fputs(line.c_str(), file_);
  std::fputc('\n', file_);
  std::fclose(file_);
  file_ = nullptr;
  std::ofstream(dir_ / "plot.svg") << render_svg({&summary_.record()});
  std::ofstream(dir_ / "plot.html") << render_html({&summary_.record()});
}

}  // namespace cellctl::journal

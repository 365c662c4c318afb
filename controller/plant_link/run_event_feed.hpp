#pragma once
// The run's events on their way from the journal's writer thread (one producer: it listens to the
// run, journal::EventListener) to one consumer thread (the plant link's, the web page's pump: pop),
// through a bounded lock-free queue, each copied into a RunEvent of its own. The writer never waits: a
// full queue drops the event and counts it.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>

#include "journal/event_listener.hpp"
#include "plant_link/run_event.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::plant_link {

class RunEventFeed final : public journal::EventListener {
 public:
  void on_event(const journal::Event& e) override {
    if (const auto copy = run_event_of(e)) push(*copy);
  }
  void on_note(double t, std::string_view text) override { push(note_event(t, text)); }

  [[nodiscard]] std::optional<RunEvent> pop() noexcept { return queue_->pop(); }
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(); }

 private:
  void push(const RunEvent& e) noexcept {
    if (!queue_->push(e)) dropped_.fetch_add(1);
  }

  std::unique_ptr<wire::SpscQueue<RunEvent, 1024>> queue_ =
      std::make_unique<wire::SpscQueue<RunEvent, 1024>>();
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace cellctl::plant_link

#pragma once
// The run's events on their way from the journal's writer thread (one producer: push) to one
// consumer thread (the plant link's, the web page's pump: pop), through a bounded lock-free queue.
// The writer never waits: a full queue drops the event and counts it.

#include <atomic>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "plant_link/run_event.hpp"
#include "wire/spsc_queue.hpp"

namespace cellctl::plant_link {

class RunEventFeed {
 public:
  // The journal's writer thread: a journal line (journal::Journal::on_line).
  void push(const nlohmann::json& line) noexcept {
    try {
      const auto e = run_event_of(line);
      if (e && !queue_->push(*e)) dropped_.fetch_add(1);
    } catch (const std::exception&) {
      dropped_.fetch_add(1);  // a line of an unexpected shape: not the run's business
    }
  }
  [[nodiscard]] std::optional<RunEvent> pop() noexcept { return queue_->pop(); }
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(); }

 private:
  std::unique_ptr<wire::SpscQueue<RunEvent, 1024>> queue_ =
      std::make_unique<wire::SpscQueue<RunEvent, 1024>>();
  std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace cellctl::plant_link

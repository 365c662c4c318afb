#pragma once
// The cell on the plant's MQTT broker: PackML tags out, commands in (packml_tags.hpp lists the topics).
//
// The control loop never waits on the network. The run's events reach the link from the journal's
// writer thread through a bounded lock-free queue (events(): full → dropped and counted); the
// status comes from the run's StatusBoard (a sequence lock the cycle never waits on); the link's own
// thread does everything else: connecting with back-off, publishing, receiving commands. A lost broker
// changes nothing in the run: the link reconnects (back-off doubling from reconnect_min_ms to
// reconnect_max_ms), publishes the retained tags again (current, not as they were), and counts the
// status messages and events it could not deliver.
//
// Only a command meant now is obeyed. The link connects with a clean session (nothing queued while it
// was away is delivered) and, in MQTT 5, subscribes to its commands so that the broker sends no
// retained message and shows the retain flag as published; every message with the retain flag — a
// 3.1.1 broker's stored one, or one published retained while the link listens — is answered, journaled
// and counted, never obeyed. Answers and status expire at the broker (MQTT 5), so nobody is handed a
// stale one later.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "plant_link/link_config.hpp"
#include "plant_link/run_access.hpp"
#include "plant_link/run_event_feed.hpp"

namespace cellctl::plant_link {

struct LinkCounters {
  bool connected = false;
  std::uint64_t connects = 0;           // CONNACKs accepted
  std::uint64_t connection_losses = 0;  // the broker gone after a connect
  std::uint64_t refused_connects = 0;   // CONNACK refused (credentials, ACL)
  std::uint64_t dropped_events = 0;     // run events the link's queue had no room for
  std::uint64_t dropped_status = 0;     // status messages not sent while disconnected
  std::uint64_t commands = 0;           // commands received
  std::uint64_t refused_commands = 0;   // answered ok:false
  std::uint64_t ignored_retained = 0;   // commands with the retain flag: answered, journaled, never obeyed
};

class PlantLink {
 public:
  // Starts the link's thread; connecting happens there. Throws std::runtime_error for options the
  // MQTT library refuses (TLS files).
  PlantLink(LinkConfig config, const config::CellCore& cell, RunAccess run);
  // Publishes online:false (a clean end: the broker discards the will), disconnects, joins.
  ~PlantLink();
  PlantLink(const PlantLink&) = delete;
  PlantLink& operator=(const PlantLink&) = delete;

  // What the run's journal tells (one producer, its writer thread): never blocks.
  [[nodiscard]] journal::EventListener& events() noexcept { return events_; }

  [[nodiscard]] LinkCounters counters() const noexcept;
  [[nodiscard]] const LinkConfig& config() const noexcept { return config_; }

 private:
  void run_thread();

  LinkConfig config_;
  const config::CellCore& cell_;
  RunAccess run_;
  RunEventFeed events_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  std::atomic<std::uint64_t> connects_{0}, losses_{0}, refused_connects_{0}, dropped_status_{0}, commands_{0},
      refused_commands_{0}, ignored_retained_{0};
  std::thread thread_;
};

}  // namespace cellctl::plant_link

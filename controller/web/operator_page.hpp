#pragma once
// The web operator page (cpp-httplib): `/` the page (page_html.hpp, no network needed), `/events`
// the live state, step, progress, axes, spindle and faults as server-sent events, `POST /cmd/<word>`
// the operator's commands (hold, unhold, stop, abort, reset; under `cellctl serve` also start, home
// and teach-in, their fields in a JSON body) — each needs the page's token in the
// X-Cellctl-Token header (or Authorization: Bearer), else 401 and nothing is done — and `/metrics`
// in the Prometheus text format.
//
// Like the plant link, it never touches the control loop: the run's events come from the journal's
// writer thread through a bounded lock-free queue, the status from the run's StatusBoard, commands go
// through the operator's one command path (plant_link::CommandDesk → CellRun::request) and are
// answered with the run's own outcome.

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/cell_mirror.hpp"
#include "plant_link/command_desk.hpp"
#include "plant_link/plant_link.hpp"
#include "plant_link/run_event_feed.hpp"

namespace httplib {
class Server;
}

namespace cellctl::web {

struct PageOptions {
  std::string address = "127.0.0.1";  // loopback unless asked otherwise
  int port = 8080;
  std::string token;  // required for every command; never empty
  std::filesystem::path recipes = "recipes";
};

// "ADDR:PORT" or "PORT" (loopback); nullopt with `why` filled when it is neither.
[[nodiscard]] std::optional<PageOptions> parse_listen_address(std::string_view text, std::string& why);

class OperatorPage {
 public:
  // Binds the address (throws std::runtime_error naming it when it cannot) and serves on threads of
  // its own until destroyed.
  OperatorPage(PageOptions options, const config::CellCore& cell, plant_link::RunAccess run);
  ~OperatorPage();
  OperatorPage(const OperatorPage&) = delete;
  OperatorPage& operator=(const OperatorPage&) = delete;

  // The journal's writer thread (one producer): never blocks.
  void on_journal_line(const nlohmann::json& line) noexcept;
  [[nodiscard]] int port() const noexcept { return port_; }

 private:
  void pump();
  [[nodiscard]] nlohmann::json status_json();
  [[nodiscard]] nlohmann::json admin_json();
  [[nodiscard]] std::string metrics_text();
  [[nodiscard]] nlohmann::json command(const std::string& word, const std::string& body,
                                       const command::CommandSource& source);

  PageOptions options_;
  const config::CellCore& cell_;
  plant_link::RunAccess run_;
  plant_link::RunEventFeed events_;
  std::mutex mutex_;  // mirror, desk, answers: the pump and the server's threads
  std::condition_variable answered_;
  plant_link::CellMirror mirror_;
  plant_link::CommandDesk desk_;
  std::vector<nlohmann::json> answers_;  // the run's answers, until the request waiting for each takes it
  std::uint64_t next_id_ = 1;
  std::uint64_t admin_version_ = 0;
  std::uint64_t commands_ = 0, refused_ = 0, unauthorised_ = 0;
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread pump_thread_;
  std::thread server_thread_;
};

}  // namespace cellctl::web

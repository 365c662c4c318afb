#pragma once
// The web operator page (cpp-httplib): `/` the page (page_html.hpp: /page.css and /page.js beside
// it, no network needed), `POST /login` a session for the page's token, `/events` the live state,
// step, progress, axes, spindle and faults as server-sent events, `POST /cmd/<word>` the operator's
// commands (hold, unhold, stop, abort, reset, clear; under `cellctl serve` also start, home and
// teach-in, their fields in a JSON body), `/metrics` in the Prometheus text format; `/recipes` the
// recipes a start may name (recipe_list.hpp), `/runs` the run history and `/runs/<run>/plot.html`,
// `plot.svg` and `report` each run's plot and report (run_history.hpp).
//
// Every request is judged on its headers before its body is read (request_guard.hpp: Host and
// Origin, size, the token or the session, the back-off of wrong tokens); the server is set up so that
// a stop always has a worker (page_server.hpp). Live-event readers are capped (max_streams; more
// are answered 503 at once). A command is stamped when its headers are read, and one that could set
// the cell moving is not obeyed when its client has gone — asked when its worker takes it up and
// again at the hand-over (hand_over.hpp) — counted in the arbiter's `ignored`; a stop, an abort or a
// hold always is obeyed. Answers carry their kind in the HTTP status (answer_status.hpp: 409 refused
// by the state, 410 expired or abandoned, …), the words in the JSON body.
//
// Like the plant link, it never touches the control loop: the run's events come from the journal's
// writer thread through a bounded lock-free queue (events()), the status from the run's StatusBoard, commands
// go through the operator's one command path (plant_link::CommandDesk → the arbiter) and are answered with
// the run's own outcome.

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "config/cell_core.hpp"
#include "plant_link/cell_mirror.hpp"
#include "plant_link/command_desk.hpp"
#include "plant_link/plant_link.hpp"
#include "plant_link/run_event_feed.hpp"
#include "web/page_options.hpp"
#include "web/request_guard.hpp"

namespace httplib {
class Server;
}

namespace cellctl::web {

class OperatorPage {
 public:
  // Binds the address (throws std::runtime_error naming it when it cannot, or when listen_problem()
  // refuses the options) and serves on threads of its own until destroyed.
  OperatorPage(PageOptions options, const config::CellCore& cell, plant_link::RunAccess run);
  ~OperatorPage();
  OperatorPage(const OperatorPage&) = delete;
  OperatorPage& operator=(const OperatorPage&) = delete;

  // What the run's journal tells (one producer, its writer thread): never blocks.
  [[nodiscard]] journal::EventListener& events() noexcept { return events_; }
  [[nodiscard]] int port() const noexcept { return port_; }

 private:
  void route();
  void pump();
  // The live events' payloads: the status, and the admin tag with each active fault's remedy.
  [[nodiscard]] std::string status_payload();
  [[nodiscard]] std::string admin_payload();
  // Axes, devices and the buttons the state allows (cell_board.hpp, command_buttons.hpp).
  [[nodiscard]] std::string board_payload();
  [[nodiscard]] std::string metrics_text();
  [[nodiscard]] schema::CommandAnswer command(const std::string& word, const std::string& body,
                                              const command::CommandSource& source,
                                              command::SteadyTime received);

  PageOptions options_;
  const config::CellCore& cell_;
  plant_link::RunAccess run_;
  plant_link::RunEventFeed events_;
  RequestGuard guard_;
  std::mutex mutex_;  // mirror, answers: the pump and the server's threads
  std::condition_variable answered_;
  plant_link::CellMirror mirror_;
  std::vector<std::string> axis_names_;
  std::optional<status::StatusView> last_view_;  // the run's, kept by the pump: the last job's between jobs
  plant_link::CommandDesk desk_;
  std::vector<schema::CommandAnswer>
      answers_;  // the run's answers, until the request waiting for each takes it
  std::uint64_t next_id_ = 1;
  std::uint64_t admin_version_ = 0;
  std::uint64_t commands_ = 0, refused_ = 0;
  std::atomic<std::uint64_t> commands_unauthorised_{0}, commands_abandoned_{0};
  std::atomic<std::size_t> streams_{0};
  std::atomic<std::uint64_t> streams_refused_{0};
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread pump_thread_;
  std::thread server_thread_;
};

}  // namespace cellctl::web

#include "plant_link/run_access.hpp"

namespace cellctl::plant_link {

LiveRun live_run(const status::StatusBoard& board) {
  LiveRun live{board.read(), {}};
  live.label = std::string(live.view.label);
  live.view.label = {};
  return live;
}

RunAccess fixed_run(command::Arbiter& arbiter, const status::StatusBoard& board, std::string mode) {
  RunAccess a;
  a.arbiter = &arbiter;
  a.status = [&board]() -> std::optional<LiveRun> { return live_run(board); };
  a.mode = std::move(mode);
  return a;
}

}  // namespace cellctl::plant_link

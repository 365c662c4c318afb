#include "plant_link/run_access.hpp"

namespace cellctl::plant_link {

LiveRun live_run(const runtime::StatusBoard& board) {
  LiveRun live{board.read(), {}};
  live.label = std::string(live.view.label);
  live.view.label = {};
  return live;
}

RunAccess fixed_run(std::function<void(supervisor::Command)> request, const runtime::StatusBoard& board,
                    std::string mode) {
  RunAccess a;
  a.request = [request = std::move(request)](supervisor::Command c) {
    request(c);
    return Taken{Taken::How::by_run, {}};
  };
  a.status = [&board]() -> std::optional<LiveRun> { return live_run(board); };
  a.mode = std::move(mode);
  return a;
}

}  // namespace cellctl::plant_link

#pragma once
// A web command is obeyed only if its client is still there when it is handed over to the cell, not
// only when a worker took it up. For a start (a recipe, homing, a Teach-In) the hand-over is the
// arbiter's `begin` — after the recipe was validated, which may take a while. The page cannot ask
// there through the command desk (the plant link's too), so it wraps the RunAccess's start: a worker
// names its client's watch for as long as it hands its command over (ClientAtHandOver, on its own
// thread), and the wrapped start asks it just before the job is registered, under the arbiter's lock
// (one poll(2): client_watch.hpp). Other commands have nothing slow between the page's own check and
// the arbiter (a bounded parse of at most 64 KiB): that check stands for theirs.

#include <functional>
#include <string_view>

#include "plant_link/run_access.hpp"

namespace cellctl::web {

// The reason a command is not obeyed when its client has gone.
inline constexpr std::string_view kClientGone = "not obeyed: its client has gone";

class ClientAtHandOver {
 public:
  // While this object lives, a start on this thread asks `gone` first.
  explicit ClientAtHandOver(std::function<bool()> gone);
  ~ClientAtHandOver();
  ClientAtHandOver(const ClientAtHandOver&) = delete;
  ClientAtHandOver& operator=(const ClientAtHandOver&) = delete;

  // A start was refused at its hand-over because its client had gone.
  [[nodiscard]] bool abandoned() const noexcept { return abandoned_; }

 private:
  friend plant_link::RunAccess starts_for_present_clients(plant_link::RunAccess run);
  std::function<bool()> gone_;
  bool abandoned_ = false;
  ClientAtHandOver* outer_;
};

// `run`, whose start refuses (kClientGone, nothing registered) when the client named on this thread
// has gone. A start without a ClientAtHandOver on its thread is not judged here.
[[nodiscard]] plant_link::RunAccess starts_for_present_clients(plant_link::RunAccess run);

}  // namespace cellctl::web

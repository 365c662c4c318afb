#include "web/hand_over.hpp"

#include <string>

namespace cellctl::web {
namespace {

// The client of the command this thread is handing over, if any.
thread_local ClientAtHandOver* t_handing_over = nullptr;

}  // namespace

ClientAtHandOver::ClientAtHandOver(std::function<bool()> gone)
    : gone_(std::move(gone)), outer_(t_handing_over) {
  t_handing_over = this;
}

ClientAtHandOver::~ClientAtHandOver() {
  t_handing_over = outer_;
}

plant_link::RunAccess starts_for_present_clients(plant_link::RunAccess run) {
  if (!run.start) return run;  // `cellctl run`: no start to hand over
  run.start = [inner = std::move(run.start)](const plant_link::StartRequest& r,
                                             const command::CommandSource& by) {
    if (auto* const client = t_handing_over; client && client->gone_()) {
      client->abandoned_ = true;
      return plant_link::Taken{plant_link::Taken::How::refused, std::string(kClientGone)};
    }
    return inner(r, by);
  };
  return run;
}

}  // namespace cellctl::web

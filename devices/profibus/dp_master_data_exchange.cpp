// profibus::DpMaster: the cyclic data exchange — outputs out and inputs back on a fixed grid, a reply
// that is not our inputs refused, the inputs' age and the cycle's statistics, DH (a diagnosis to read),
// and Global_Control broadcast between two exchanges.
#include <algorithm>

#include "profibus/dp_master.hpp"
#include "profibus/fdl_codes.hpp"

namespace cellctl::profibus {
namespace {

bool is_data_reply(const FdlFrame& f) noexcept {
  if (f.kind == FrameKind::short_ack) return true;
  const std::uint8_t code = fc::function(f.fc);
  return code == fc::kDataLow || code == fc::kDataHigh || code == fc::kOk;
}

}  // namespace

link::Duration DpMaster::input_age(link::TimePoint now) const noexcept {
  const link::TimePoint since = stats_.last_input_at.value_or(activated_at_);
  return now > since ? now - since : link::Duration{0};
}

bool DpMaster::set_outputs(std::span<const std::uint8_t> outputs) noexcept {
  if (outputs.size() != setup_.output_length) return false;
  (void)outputs_.assign(outputs);  // fits: output_length is at most kMaxIo (checked at construction)
  return true;
}

void DpMaster::reject_input() noexcept {
  ++stats_.bad_inputs;
  stats_.last_input_at = previous_input_at_;
}

bool DpMaster::global_control(std::uint8_t commands) noexcept {
  if (lifecycle_ == link::Lifecycle::inactive || global_control_) return false;
  global_control_ = GlobalControl{commands, config_.group};
  return true;
}

// One Data_Exchange: our outputs out, the slave's inputs back (on_data), on a fixed grid.
void DpMaster::send_data_exchange(link::TimePoint now) {
  send(make_frame(setup_.station_address, config_.master_address, next_fc(fc::kSrdHigh), outputs_.view()),
       true, Pending::cyclic, now);
  // A fixed grid, skipping ahead after an overrun rather than bursting to catch up.
  next_cycle_at_ = std::max(next_cycle_at_ + config_.data_exchange_period, now);
}

// The Global_Control waiting since global_control(), broadcast between two Data_Exchanges.
void DpMaster::send_global_control(link::TimePoint now) {
  std::array<std::uint8_t, kGlobalControlSize> data{};
  (void)encode(*global_control_, data);  // fills `data`, the service's size
  global_control_.reset();
  send(make_sap_frame(kBroadcastAddress, config_.master_address,
                      static_cast<std::uint8_t>(fc::kRequest | fc::kSdnHigh), sap::kGlobalControl,
                      sap::kMaster, data),
       false, Pending::global_control, now);
}

void DpMaster::on_data(const FdlFrame& reply, link::TimePoint now) {
  if (!is_data_reply(reply)) {
    ++health_.error_replies;
    restart(now, "slave refused Data_Exchange (not in data exchange)");
    return;
  }
  if (reply.data.size() != setup_.input_length) {
    // Not our inputs: a slave that answers with another shape is not in the exchange we configured.
    ++stats_.bad_inputs;
    restart_with_bad_reply(now, "Data_Exchange", reply.data.size(), setup_.input_length, setup_.input_length);
    return;
  }
  (void)inputs_.assign(reply.data.view());  // input_length octets, checked above
  ++stats_.data_exchanges;
  previous_input_at_ = stats_.last_input_at;
  if (stats_.last_input_at) {
    stats_.last_cycle = now - *stats_.last_input_at;
    stats_.max_cycle = std::max(stats_.max_cycle, stats_.last_cycle);
  }
  stats_.last_input_at = now;
  if (reply.kind != FrameKind::short_ack && fc::function(reply.fc) == fc::kDataHigh) {
    // DH: the slave has a diagnosis for us; read it before the next exchange.
    state_ = DpState::diag_cyclic;
  }
}

}  // namespace cellctl::profibus

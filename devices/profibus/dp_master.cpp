// profibus::DpMaster: the master's lifecycle and its line — the configuration checked at construction,
// activate and deactivate, one poll (octets in, the reply matched to the request in flight, the slot
// time, retries with the same FCB, a slave lost), FCB/FCV per station, TSYN before every request, the
// state changes and restarts, and Set_Slave_Add. What is sent and judged in start-up and in data
// exchange is in dp_master_startup.cpp and dp_master_data_exchange.cpp.
#include "profibus/dp_master.hpp"

#include <algorithm>
#include <stdexcept>

#include "link/fault_reason.hpp"
#include "profibus/bus_timing.hpp"
#include "profibus/fdl_codes.hpp"

namespace cellctl::profibus {

std::string_view to_string(DpState s) noexcept {
  switch (s) {
    case DpState::stopped:
      return "stopped";
    case DpState::wait_address:
      return "wait_address";
    case DpState::fdl_status:
      return "fdl_status";
    case DpState::diag_initial:
      return "diag_initial";
    case DpState::set_prm:
      return "set_prm";
    case DpState::chk_cfg:
      return "chk_cfg";
    case DpState::diag_check:
      return "diag_check";
    case DpState::data_exchange:
      return "data_exchange";
    case DpState::diag_cyclic:
      return "diag_cyclic";
    case DpState::refused:
      return "refused";
    case DpState::restart_wait:
      return "restart_wait";
    case DpState::clearing:
      return "clearing";
  }
  return "?";
}

namespace {

constexpr std::string_view kSlaveLost = "slave lost: no good reply within lost_slave_time";

void require(bool ok, const char* field, unsigned value, const char* rule) {
  if (!ok)
    throw std::invalid_argument(std::string("profibus master: ") + field + ": " + std::to_string(value) +
                                ": " + rule);
}

bool is_reply_from(const FdlFrame& f, std::uint8_t master, std::uint8_t station) noexcept {
  if (f.kind == FrameKind::short_ack) return true;
  if (f.kind == FrameKind::token || fc::is_request(f.fc)) return false;
  return f.da == master && f.sa == station;
}

}  // namespace

DpMaster::DpMaster(link::Link& link, const DpMasterConfig& config, const DpSlaveSetup& setup)
    : link_(link),
      config_(config),
      setup_(setup),
      char_time_(config.line.char_time()),
      tsyn_(config.line.baud ? bit_times(config.line, kTsynBits) : link::Duration{}),
      slot_time_(config.line.baud ? bit_times(config.line, config.slot_time_bits) : link::Duration{}) {
  require(config.line.baud > 0, "line.baud", config.line.baud, "must be positive");
  require(config.master_address <= kMaxMasterAddress, "master_address", config.master_address,
          "outside 0..125");
  require(config.slot_time_bits > 0, "slot_time_bits", config.slot_time_bits, "must be positive");
  require(setup.station_address >= 1 && setup.station_address <= kDefaultSlaveAddress, "station_address",
          setup.station_address, "outside 1..126");
  require(setup.station_address != config.master_address, "station_address", setup.station_address,
          "equals the master address");
  require(setup.input_length <= kMaxIo, "input_length", static_cast<unsigned>(setup.input_length),
          "above 244 octets");
  require(setup.output_length <= kMaxIo, "output_length", static_cast<unsigned>(setup.output_length),
          "above 244 octets");
  outputs_.resize(setup.output_length);
  inputs_.resize(setup.input_length);
  // Reserved once so that reasons written in poll() never allocate.
  fault_reason_.reserve(link::kFaultReasonCapacity);
  restart_reason_.reserve(link::kFaultReasonCapacity);
}

void DpMaster::activate(link::TimePoint now) {
  lifecycle_ = link::Lifecycle::activating;
  activated_at_ = now;
  startup_fault_ = {};
  fault_reason_.clear();
  in_flight_ = false;
  decoder_.reset();
  line_idle_from_ = now - tsyn_;
  enter(setup_.station_address == kDefaultSlaveAddress ? DpState::wait_address : DpState::fdl_status, now);
}

void DpMaster::set_slave_setup(const DpSlaveSetup& setup) noexcept {
  if (lifecycle_ != link::Lifecycle::inactive && lifecycle_ != link::Lifecycle::fault) return;
  setup_ = setup;
}

void DpMaster::deactivate(link::TimePoint now) {
  if (lifecycle_ == link::Lifecycle::inactive) return;
  if (state_ == DpState::data_exchange || state_ == DpState::diag_cyclic) {
    lifecycle_ = link::Lifecycle::deactivating;
    enter(DpState::clearing, now);
    return;
  }
  in_flight_ = false;
  lifecycle_ = link::Lifecycle::inactive;
  enter(DpState::stopped, now);
}

bool DpMaster::set_slave_address(std::uint8_t new_address, bool no_add_chg) noexcept {
  if (lifecycle_ == link::Lifecycle::inactive || address_change_ == RequestStatus::pending) return false;
  if (new_address < 1 || new_address > kMaxMasterAddress || new_address == config_.master_address)
    return false;
  address_request_ = SetSlaveAdd{new_address, setup_.ident, no_add_chg};
  address_change_ = RequestStatus::pending;
  return true;
}

link::Lifecycle DpMaster::poll(link::TimePoint now) {
  std::array<std::uint8_t, 256> chunk{};
  for (;;) {
    const auto r = link_.read(chunk);
    if (!r.ok() || r.count == 0) break;
    line_idle_from_ = now;  // the line was busy until now: TSYN counts from here
    // What does not fit (more than two longest frames in one poll, on a bus where one reply answers
    // one request: noise) is dropped; a reply lost in it comes again on the retry.
    (void)decoder_.push(std::span<const std::uint8_t>(chunk.data(), r.count));
    if (in_flight_ && expect_reply_ && !reply_started_) {
      // The reply has begun within the slot time: give it the time of a longest frame to finish.
      reply_started_ = true;
      reply_deadline_ = now + char_time_ * static_cast<int>(kMaxFrameSize) + slot_time_;
    }
  }
  while (auto ev = decoder_.next()) {
    if (ev->error != FdlError::none) {
      ++health_.bad_frames;
      continue;
    }
    if (in_flight_ && expect_reply_ &&
        is_reply_from(ev->frame, config_.master_address, setup_.station_address))
      on_reply(ev->frame, now);
  }
  if (in_flight_ && expect_reply_ && now >= reply_deadline_) on_no_reply(now);
  // Checked every poll, not only when a request has gone unanswered through its retries: noise that
  // looks like the start of a reply holds the reply deadline out by a longest frame's time (150 ms at
  // 19.2 kbaud), and a line kept busy holds every request back (TSYN never passes). A reply still on
  // its way after lost_slave_time is no longer waited for.
  if ((state_ == DpState::data_exchange || state_ == DpState::diag_cyclic) &&
      pending_ != Pending::set_address && health_.silent_for(now, state_since_) >= config_.lost_slave_time) {
    in_flight_ = false;
    pending_ = Pending::none;
    ++stats_.lost;
    restart(now, kSlaveLost);
  }
  if (!in_flight_ && now >= line_idle_from_ + tsyn_) next_request(now);
  return lifecycle_;
}

std::optional<link::TimePoint> DpMaster::next_deadline() const noexcept {
  if (in_flight_) return reply_deadline_;
  const link::TimePoint line_free = line_idle_from_ + tsyn_;
  if (address_request_ || (global_control_ && state_ == DpState::data_exchange)) return line_free;
  if (!has_request(link::TimePoint::max())) return std::nullopt;
  return std::max(line_free, next_cycle_at_);
}

// Whether the state has a cyclic request to send at `now`.
bool DpMaster::has_request(link::TimePoint now) const noexcept {
  switch (state_) {
    case DpState::stopped:
    case DpState::wait_address:
    case DpState::refused:
      return false;
    default:
      return now >= next_cycle_at_;
  }
}

std::uint8_t DpMaster::next_fc(std::uint8_t function) noexcept {
  auto& st = fcb_[setup_.station_address];
  if (function == fc::kFdlStatus) {
    st = {};  // the next request to this station starts the FCB sequence again
    return static_cast<std::uint8_t>(fc::kRequest | function);
  }
  std::uint8_t code = static_cast<std::uint8_t>(fc::kRequest | function | (st.fcb ? fc::kFcb : 0));
  if (st.started) code = static_cast<std::uint8_t>(code | fc::kFcv);
  st.started = true;
  st.fcb = !st.fcb;
  return code;
}

FdlFrame DpMaster::sap_request(std::uint8_t dsap, std::span<const std::uint8_t> data) noexcept {
  return make_sap_frame(setup_.station_address, config_.master_address, next_fc(fc::kSrdHigh), dsap,
                        sap::kMaster, data);
}

void DpMaster::send(const FdlFrame& frame, bool expect_reply, Pending pending, link::TimePoint now) {
  request_bytes_.resize(encode(frame, request_bytes_.storage()));
  expect_reply_ = expect_reply;
  pending_ = pending;
  attempts_ = 0;
  transmit(now);
}

void DpMaster::transmit(link::TimePoint now) {
  decoder_.reset();  // octets from before this request cannot be its reply
  // A request the port did not take whole goes unanswered: the reply time-out and the retries see to
  // it, and a port that is gone shows on the next read.
  (void)link_.write(request_bytes_.view());
  sent_at_ = now;
  const link::TimePoint request_end = now + char_time_ * static_cast<int>(request_bytes_.size());
  line_idle_from_ = request_end;
  reply_deadline_ = request_end + slot_time_;
  reply_started_ = false;
  in_flight_ = expect_reply_;
}

void DpMaster::next_request(link::TimePoint now) {
  if (address_request_) {
    std::array<std::uint8_t, kSetSlaveAddSize> data{};
    (void)encode(*address_request_, data);  // fills `data`, the service's size
    send(sap_request(sap::kSetSlaveAdd, data), true, Pending::set_address, now);
    return;
  }
  if (global_control_ && state_ == DpState::data_exchange) {
    send_global_control(now);
    return;
  }
  if (!has_request(now)) return;
  switch (state_) {
    case DpState::restart_wait:
    case DpState::fdl_status:
    case DpState::diag_initial:
    case DpState::set_prm:
    case DpState::chk_cfg:
    case DpState::diag_check:
    case DpState::diag_cyclic:
      send_startup_request(now);
      return;
    case DpState::data_exchange:
      send_data_exchange(now);
      return;
    case DpState::clearing:
      send_clear_data(now);
      return;
    case DpState::stopped:
    case DpState::wait_address:
    case DpState::refused:
      return;
  }
}

// deactivate() from data exchange: Global_Control Clear_Data to the slave (it clears its outputs), sent
// without acknowledgement (SDN), then stopped: nothing to wait for.
void DpMaster::send_clear_data(link::TimePoint now) {
  const GlobalControl clear{static_cast<std::uint8_t>(GlobalCommand::clear_data), 0};
  std::array<std::uint8_t, kGlobalControlSize> data{};
  (void)encode(clear, data);  // fills `data`, the service's size
  send(make_sap_frame(setup_.station_address, config_.master_address,
                      static_cast<std::uint8_t>(fc::kRequest | fc::kSdnHigh), sap::kGlobalControl,
                      sap::kMaster, data),
       false, Pending::global_control, now);
  lifecycle_ = link::Lifecycle::inactive;
  enter(DpState::stopped, now);
}

void DpMaster::on_reply(const FdlFrame& reply, link::TimePoint now) {
  in_flight_ = false;
  line_idle_from_ = now;
  health_.record_reply(sent_at_, now);
  const Pending pending = pending_;
  pending_ = Pending::none;
  if (pending == Pending::set_address) {
    const std::uint8_t new_address = address_request_->new_address;
    address_request_.reset();
    if (reply.kind != FrameKind::short_ack) {
      ++health_.error_replies;
      address_change_ = RequestStatus::failed;
      return;
    }
    // Follow the slave to its new address and start it up there.
    address_change_ = RequestStatus::done;
    setup_.station_address = new_address;
    if (lifecycle_ != link::Lifecycle::fault) lifecycle_ = link::Lifecycle::activating;
    enter(DpState::fdl_status, now);
    return;
  }
  if (state_ == DpState::data_exchange) {
    on_data(reply, now);
    return;
  }
  on_startup_reply(reply, now);
}

void DpMaster::on_no_reply(link::TimePoint now) {
  ++health_.timeouts;
  if (attempts_ < config_.max_retries) {
    // The same octets, hence the same FCB: a slave that did execute the request only answers again.
    ++attempts_;
    ++health_.retries;
    transmit(now);
    return;
  }
  in_flight_ = false;
  line_idle_from_ = now;
  const Pending pending = pending_;
  pending_ = Pending::none;
  if (pending == Pending::set_address) {
    address_request_.reset();
    address_change_ = RequestStatus::failed;
    return;
  }
  if (state_ == DpState::clearing) return;  // deactivating: the Clear_Data goes out regardless
  // In data exchange an unanswered request is retried; poll() judges lost_slave_time, every poll.
  if (state_ == DpState::data_exchange || state_ == DpState::diag_cyclic) return;
  restart(now, "no reply during start-up");
}

void DpMaster::enter(DpState s, link::TimePoint now) {
  state_ = s;
  state_since_ = now;
  next_cycle_at_ = now;
  if (s == DpState::fdl_status) ++stats_.startups;
  if (s == DpState::restart_wait) next_cycle_at_ = now + config_.restart_delay;
}

void DpMaster::restart(link::TimePoint now, std::string_view why) {
  restart_reason_.assign(why.substr(0, restart_reason_.capacity()));
  if (lifecycle_ != link::Lifecycle::fault) lifecycle_ = link::Lifecycle::activating;
  enter(DpState::restart_wait, now);
}

void DpMaster::restart_with_bad_reply(link::TimePoint now, std::string_view service, std::size_t octets,
                                      std::size_t fewest, std::size_t most) {
  ++health_.error_replies;
  if (lifecycle_ != link::Lifecycle::fault) lifecycle_ = link::Lifecycle::activating;
  if (fewest == most)
    link::assign_formatted(restart_reason_,
                           "{} reply of {} octets, {} expected: not taken, start-up begun again", service,
                           octets, fewest);
  else
    link::assign_formatted(restart_reason_,
                           "{} reply of {} octets, {} to {} expected: not taken, start-up begun again",
                           service, octets, fewest, most);
  enter(DpState::restart_wait, now);
}

}  // namespace cellctl::profibus

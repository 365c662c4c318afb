#include "profibus/dp_slave.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "profibus/bus_timing.hpp"
#include "profibus/dp_services.hpp"
#include "profibus/fdl_codes.hpp"

namespace cellctl::profibus {

std::string_view to_string(DpSlaveState s) noexcept {
  switch (s) {
    case DpSlaveState::wait_prm:
      return "Wait_Prm";
    case DpSlaveState::wait_cfg:
      return "Wait_Cfg";
    case DpSlaveState::data_exchange:
      return "Data_Exchange";
  }
  return "?";
}

namespace {
constexpr std::uint8_t kMinTsdrFloor = 11;  // the standard's smallest min_TSDR
constexpr auto kWatchdogUnit = std::chrono::milliseconds(10);

FdlFrame status_reply(const FdlFrame& request, std::uint8_t own, std::uint8_t code) noexcept {
  return make_frame(request.sa, own, static_cast<std::uint8_t>(code | fc::kStationSlave));
}
}  // namespace

DpSlave::DpSlave(link::Link& link, const DpSlaveConfig& config, SlaveBehaviour& behaviour)
    : link_(link),
      config_(config),
      behaviour_(behaviour),
      address_(config.address),
      min_tsdr_(bit_times(config.line, kMinTsdrFloor)) {
  if (config.address < 1 || config.address > kDefaultSlaveAddress)
    throw std::invalid_argument("profibus slave: address: " + std::to_string(config.address) +
                                " is outside 1..126");
  if (config.line.baud == 0) throw std::invalid_argument("profibus slave: line.baud: 0");
}

void DpSlave::poll(link::TimePoint now) {
  std::array<std::uint8_t, 256> chunk{};
  for (;;) {
    const auto r = link_.read(chunk);
    if (!r.ok() || r.count == 0) break;
    if (silent_) continue;
    // Takes it all: the frames are drained below before the next read, which leaves less than a frame
    // beside the chunk in a decoder that holds two.
    (void)decoder_.push(std::span<const std::uint8_t>(chunk.data(), r.count));
    while (auto ev = decoder_.next()) {
      if (ev->error != FdlError::none) {
        ++counters_.bad_frames;
        continue;
      }
      handle(ev->frame, now);
    }
  }
  if (silent_) {
    decoder_.reset();
    reply_due_.reset();
  }
  check_watchdog(now);
  send_due(now);
}

std::optional<link::TimePoint> DpSlave::next_deadline() const noexcept {
  if (reply_due_ && watchdog_deadline_) return std::min(*reply_due_, *watchdog_deadline_);
  return reply_due_ ? reply_due_ : watchdog_deadline_;
}

StandardDiag DpSlave::standard_diag() const {
  StandardDiag d;
  d.station_not_ready = state_ != DpSlaveState::data_exchange;
  d.cfg_fault = cfg_fault_;
  d.prm_fault = prm_fault_;
  d.not_supported = not_supported_;
  d.ext_diag = behaviour_.diag_pending();
  d.prm_req = state_ == DpSlaveState::wait_prm;
  d.stat_diag = behaviour_.static_diag();
  d.wd_on = wd_on_;
  d.freeze_mode = freeze_mode_;
  d.sync_mode = sync_mode_;
  d.master_address = master_;
  d.ident = config_.ident;
  return d;
}

void DpSlave::handle(const FdlFrame& request, link::TimePoint now) {
  if (request.kind == FrameKind::token || request.kind == FrameKind::short_ack) return;
  if (!fc::is_request(request.fc)) return;  // another station's reply
  const std::uint8_t function = fc::function(request.fc);
  const bool sdn = function == fc::kSdnLow || function == fc::kSdnHigh;
  if (request.da == kBroadcastAddress) {
    if (sdn) global_control(request);
    return;
  }
  if (request.da != address_) return;
  ++counters_.requests;
  if (master_ != kNoMaster && request.sa == master_ && watchdog_deadline_)
    watchdog_deadline_ = now + watchdog_;
  if (sdn) {
    global_control(request);
    return;
  }
  if (function != fc::kSrdLow && function != fc::kSrdHigh && function != fc::kFdlStatus) return;

  // A repeated request (FCV set, FCB as last time) was executed already: only the reply was lost.
  auto& memory = fcb_[request.sa];
  const bool fcb = (request.fc & fc::kFcb) != 0;
  const bool fcv = (request.fc & fc::kFcv) != 0;
  if (function != fc::kFdlStatus) {
    if (fcv && memory.valid && memory.fcb == fcb && last_reply_to_ == request.sa && !last_reply_.empty()) {
      ++counters_.repeats;
      pending_reply_ = last_reply_;
      reply_due_ = now + min_tsdr_;
      return;
    }
    memory = {true, fcb};
  }
  const FdlFrame reply = execute(request, now);
  pending_reply_.resize(encode(reply, pending_reply_.storage()));
  last_reply_ = pending_reply_;
  last_reply_to_ = request.sa;
  reply_due_ = now + min_tsdr_;
}

FdlFrame DpSlave::execute(const FdlFrame& request, link::TimePoint now) {
  if (fc::function(request.fc) == fc::kFdlStatus) return status_reply(request, address_, fc::kOk);
  if (request.dsap) return serve_sap(request, now);
  // Data_Exchange: only in data exchange, never at the commissioning address.
  if (state_ != DpSlaveState::data_exchange || address_ == kDefaultSlaveAddress || request.sa != master_)
    return status_reply(request, address_, fc::kNotActivated);
  return data_exchange(request);
}

FdlFrame DpSlave::serve_sap(const FdlFrame& request, link::TimePoint now) {
  const std::uint8_t ssap = request.ssap.value_or(sap::kMaster);
  const auto data = request.data.view();
  const auto answer = [&](std::span<const std::uint8_t> bytes) {
    return make_sap_frame(request.sa, address_, fc::kDataLow, ssap, *request.dsap, bytes);
  };
  const FdlFrame refused = status_reply(request, address_, fc::kNotActivated);
  const bool commissioning = address_ == kDefaultSlaveAddress;
  switch (*request.dsap) {
    case sap::kSlaveDiag:
      return diag_reply(request);
    case sap::kSetPrm:
      if (commissioning) return refused;
      return set_prm(data, request.sa, now) ? make_short_ack() : refused;
    case sap::kChkCfg:
      if (commissioning || state_ == DpSlaveState::wait_prm || request.sa != master_) return refused;
      return chk_cfg(data) ? make_short_ack() : refused;
    case sap::kGetCfg: {
      std::array<std::uint8_t, kMaxData> cfg{};
      const std::size_t n = behaviour_.real_cfg(cfg);
      return n > 0 ? answer(std::span<const std::uint8_t>(cfg.data(), n)) : answer(cfg_.view());
    }
    case sap::kRdInp:
      return answer(inputs_.view());
    case sap::kRdOutp:
      return answer(outputs_.view());
    case sap::kSetSlaveAdd:
      return set_slave_add(data) ? make_short_ack() : refused;
    default:
      return refused;
  }
}

FdlFrame DpSlave::diag_reply(const FdlFrame& request) {
  std::array<std::uint8_t, kMaxData> buf{};
  const StandardDiag standard = standard_diag();
  std::size_t n = encode(standard, buf);
  n += behaviour_.ext_diag(std::span<std::uint8_t>(buf).subspan(n, kMaxExtDiag));
  return make_sap_frame(request.sa, address_, fc::kDataLow, request.ssap.value_or(sap::kMaster),
                        sap::kSlaveDiag, std::span<const std::uint8_t>(buf.data(), n));
}

bool DpSlave::set_prm(std::span<const std::uint8_t> data, std::uint8_t master, link::TimePoint now) {
  const auto standard = decode_prm_standard(data);
  // Locked by another master: its Set_Prm is not taken (RS) and nothing changes here. Only the
  // master that holds the slave can re-parameterise or unlock it.
  if (master_ != kNoMaster && master != master_) {
    ++counters_.locked_refusals;
    return false;
  }
  if (state_ == DpSlaveState::data_exchange) leave_data_exchange(LeaveReason::new_prm);
  state_ = DpSlaveState::wait_prm;
  master_ = kNoMaster;
  watchdog_deadline_.reset();
  wd_on_ = false;
  prm_fault_ = true;
  not_supported_ = false;
  cfg_fault_ = false;
  if (!standard) {
    prm_reason_ = "Set_Prm shorter than its 7 standard octets";
    return true;  // received and judged: the verdict is in the diagnosis
  }
  if (standard->ident != config_.ident) {
    prm_reason_ = "ident number does not match the slave's";
    return true;
  }
  if ((standard->freeze_req && !config_.freeze_supported) ||
      (standard->sync_req && !config_.sync_supported)) {
    not_supported_ = true;
    prm_reason_ = "Freeze/Sync requested but not supported";
    return true;
  }
  const PrmVerdict verdict = behaviour_.check_prm(data.subspan(kPrmStandardSize));
  if (!verdict.ok) {
    prm_reason_ = verdict.reason;
    return true;
  }
  prm_fault_ = false;
  prm_reason_ = {};
  master_ = master;
  wd_on_ = standard->wd_on && standard->wd_fact_1 > 0 && standard->wd_fact_2 > 0;
  watchdog_ = kWatchdogUnit * standard->wd_fact_1 * standard->wd_fact_2;
  if (wd_on_) watchdog_deadline_ = now + watchdog_;
  min_tsdr_ = bit_times(config_.line, std::max(standard->min_tsdr_bits, kMinTsdrFloor));
  group_ = standard->group;
  freeze_enabled_ = standard->freeze_req;
  sync_enabled_ = standard->sync_req;
  state_ = DpSlaveState::wait_cfg;
  return true;
}

bool DpSlave::chk_cfg(std::span<const std::uint8_t> data) {
  if (state_ == DpSlaveState::data_exchange && std::ranges::equal(data, cfg_.view())) return true;
  if (!behaviour_.check_cfg(data)) {
    cfg_fault_ = true;
    if (state_ == DpSlaveState::data_exchange) leave_data_exchange(LeaveReason::cfg_rejected);
    state_ = DpSlaveState::wait_prm;
    return true;  // acknowledged; the verdict is Cfg_Fault in the diagnosis
  }
  cfg_fault_ = false;
  (void)cfg_.assign(data);  // a data unit: at most kMaxData octets, as cfg_
  outputs_.clear();
  synced_outputs_.clear();
  state_ = DpSlaveState::data_exchange;
  behaviour_.on_data_exchange_entered();
  return true;
}

FdlFrame DpSlave::data_exchange(const FdlFrame& request) {
  ++counters_.data_exchanges;
  (void)outputs_.assign(request.data.view());  // a data unit: at most kMaxData octets, as outputs_
  // In Sync mode the device keeps the outputs latched at the last Sync command.
  const auto applied = sync_mode_ ? synced_outputs_.view() : outputs_.view();
  inputs_.resize(behaviour_.exchange(applied, inputs_.storage()));
  // In Freeze mode the master reads the inputs sampled at the last Freeze command.
  const auto reply_inputs = freeze_mode_ && frozen_valid_ ? frozen_inputs_.view() : inputs_.view();
  const std::uint8_t code = behaviour_.diag_pending() ? fc::kDataHigh : fc::kDataLow;
  return make_frame(request.sa, address_, static_cast<std::uint8_t>(code | fc::kStationSlave), reply_inputs);
}

void DpSlave::global_control(const FdlFrame& request) {
  if (request.dsap != sap::kGlobalControl || state_ != DpSlaveState::data_exchange || request.sa != master_)
    return;
  const auto gc = decode_global_control(request.data.view());
  if (!gc || (gc->group_select != 0 && (gc->group_select & group_) == 0)) return;
  if (gc->has(GlobalCommand::clear_data)) {
    std::fill_n(outputs_.storage().begin(), outputs_.size(), std::uint8_t{0});
    std::fill_n(synced_outputs_.storage().begin(), synced_outputs_.size(), std::uint8_t{0});
    behaviour_.on_clear_data();
  }
  if (freeze_enabled_ && gc->has(GlobalCommand::freeze)) {
    freeze_mode_ = true;
    frozen_inputs_.resize(
        behaviour_.exchange(sync_mode_ ? synced_outputs_.view() : outputs_.view(), frozen_inputs_.storage()));
    frozen_valid_ = true;
  } else if (gc->has(GlobalCommand::unfreeze)) {
    freeze_mode_ = false;
    frozen_valid_ = false;
  }
  if (sync_enabled_ && gc->has(GlobalCommand::sync)) {
    sync_mode_ = true;
    synced_outputs_ = outputs_;
  } else if (gc->has(GlobalCommand::unsync)) {
    sync_mode_ = false;
  }
}

bool DpSlave::set_slave_add(std::span<const std::uint8_t> data) {
  const auto req = decode_set_slave_add(data);
  if (!req || !config_.address_change_allowed || address_locked_ || state_ != DpSlaveState::wait_prm)
    return false;
  if (req->ident != config_.ident || req->new_address < 1 || req->new_address > kMaxMasterAddress)
    return false;
  // The acknowledgement is a short ack (no address in it), so moving now is safe.
  address_ = req->new_address;
  address_locked_ = req->no_add_chg;
  fcb_ = {};
  behaviour_.on_address_changed(req->new_address, req->no_add_chg);
  return true;
}

void DpSlave::leave_data_exchange(LeaveReason reason) {
  state_ = DpSlaveState::wait_prm;
  freeze_mode_ = false;
  frozen_valid_ = false;
  sync_mode_ = false;
  behaviour_.on_data_exchange_left(reason);
}

void DpSlave::check_watchdog(link::TimePoint now) {
  if (!watchdog_deadline_ || now < *watchdog_deadline_) return;
  watchdog_deadline_.reset();
  ++counters_.watchdog_expiries;
  behaviour_.on_watchdog_expired();
  if (state_ == DpSlaveState::data_exchange) leave_data_exchange(LeaveReason::watchdog);
  // The slave forgets its master and waits to be parameterised again.
  state_ = DpSlaveState::wait_prm;
  master_ = kNoMaster;
  wd_on_ = false;
}

void DpSlave::send_due(link::TimePoint now) {
  if (!reply_due_ || now < *reply_due_) return;
  reply_due_.reset();
  (void)link_.write(pending_reply_.view());  // a reply lost on the line is the master's retry
}

}  // namespace cellctl::profibus

// profibus::DpMaster: the start-up, as SOEM keeps configuration apart from the cyclic work —
// FDL_Status, Slave_Diag, Set_Prm (the parameterisation), Chk_Cfg (the configuration check), Slave_Diag
// until ready — and the diagnosis, judged here in start-up and after DH alike: who refused (the slave:
// Prm_Fault, Cfg_Fault, Not_Supported, RS; our master: another ident, another master's lock) and the
// fault reason that says so.
#include <algorithm>

#include "link/fault_reason.hpp"
#include "profibus/dp_master.hpp"
#include "profibus/fdl_codes.hpp"

namespace cellctl::profibus {

std::string_view to_string(StartupFault::Kind k) noexcept {
  switch (k) {
    case StartupFault::Kind::none:
      return "none";
    case StartupFault::Kind::prm_fault:
      return "Prm_Fault";
    case StartupFault::Kind::cfg_fault:
      return "Cfg_Fault";
    case StartupFault::Kind::not_supported:
      return "Not_Supported";
    case StartupFault::Kind::ident_mismatch:
      return "ident number mismatch";
    case StartupFault::Kind::rejected:
      return "Set_Prm rejected (RS)";
    case StartupFault::Kind::master_lock:
      return "Master_Lock";
  }
  return "?";
}

// The request of a start-up state: FDL_Status (is anybody there?), Slave_Diag (also the one after DH in
// data exchange), Set_Prm with the standard octets from our config and the slave's user parameters,
// Chk_Cfg with its identifiers.
void DpMaster::send_startup_request(link::TimePoint now) {
  switch (state_) {
    case DpState::restart_wait:
      enter(DpState::fdl_status, now);
      [[fallthrough]];
    case DpState::fdl_status:
      send(make_frame(setup_.station_address, config_.master_address, next_fc(fc::kFdlStatus)), true,
           Pending::cyclic, now);
      return;
    case DpState::diag_initial:
    case DpState::diag_check:
    case DpState::diag_cyclic:
      send(sap_request(sap::kSlaveDiag, {}), true, Pending::cyclic, now);
      return;
    case DpState::set_prm: {
      std::array<std::uint8_t, kMaxData> prm{};
      PrmStandard standard;
      standard.wd_on = config_.wd_fact_1 > 0 && config_.wd_fact_2 > 0;
      standard.wd_fact_1 = config_.wd_fact_1;
      standard.wd_fact_2 = config_.wd_fact_2;
      standard.min_tsdr_bits = config_.min_tsdr_bits;
      standard.ident = setup_.ident;
      standard.group = config_.group;
      standard.freeze_req = setup_.freeze_req;
      standard.sync_req = setup_.sync_req;
      std::size_t n = encode(standard, prm);
      std::copy_n(setup_.user_prm.view().begin(), setup_.user_prm.size(), prm.begin() + static_cast<long>(n));
      n += setup_.user_prm.size();
      send(sap_request(sap::kSetPrm, std::span<const std::uint8_t>(prm.data(), n)), true, Pending::cyclic,
           now);
      return;
    }
    case DpState::chk_cfg:
      send(sap_request(sap::kChkCfg, setup_.cfg.view()), true, Pending::cyclic, now);
      return;
    default:
      return;  // not a start-up state: next_request() sends its request
  }
}

// A reply in start-up, or to a Slave_Diag (the one after DH in data exchange too: the same diagnosis,
// judged by the same rules).
void DpMaster::on_startup_reply(const FdlFrame& reply, link::TimePoint now) {
  const bool ack = reply.kind == FrameKind::short_ack;
  switch (state_) {
    case DpState::fdl_status:
      enter(DpState::diag_initial, now);
      return;
    case DpState::diag_initial:
    case DpState::diag_check:
    case DpState::diag_cyclic:
      on_diag(reply, now);
      return;
    case DpState::set_prm:
      if (!ack) {
        ++health_.error_replies;
        refuse(StartupFault::Kind::rejected);
        return;
      }
      enter(DpState::chk_cfg, now);
      return;
    case DpState::chk_cfg:
      // A refused Chk_Cfg (RS after a Prm_Fault) is explained by the diagnosis read next.
      if (!ack) ++health_.error_replies;
      enter(DpState::diag_check, now);
      return;
    default:
      return;
  }
}

void DpMaster::on_diag(const FdlFrame& reply, link::TimePoint now) {
  if (!reply.dsap) {
    ++health_.error_replies;
    restart(now, "slave answered Slave_Diag without diagnosis data (refused the service)");
    return;
  }
  const auto diag = decode_diagnosis(reply.data.view());
  if (!diag) {
    restart_with_bad_reply(now, "Slave_Diag", reply.data.size(), kStandardDiagSize, kMaxData);
    return;
  }
  diagnosis_ = *diag;
  ++stats_.diag_reads;
  StandardDiag& d = diagnosis_.standard;
  // Master_Lock is the master's bit: the slave names another master as the one that holds it.
  const bool ours = d.master_address == config_.master_address;
  d.master_lock = d.master_address != kNoMaster && !ours;
  if (d.ident != setup_.ident) return refuse(StartupFault::Kind::ident_mismatch);
  if (d.master_lock) return refuse(StartupFault::Kind::master_lock);
  if (state_ == DpState::diag_initial) return enter(DpState::set_prm, now);
  if (state_ == DpState::diag_check) {
    // Not_Supported comes with Prm_Fault: the more specific reason first.
    if (d.not_supported) return refuse(StartupFault::Kind::not_supported);
    if (d.prm_fault) return refuse(StartupFault::Kind::prm_fault);
    if (d.cfg_fault) return refuse(StartupFault::Kind::cfg_fault);
  }
  if (d.ready_for_data_exchange() && ours) {
    if (state_ == DpState::diag_check) {
      lifecycle_ = link::Lifecycle::active;
      stats_.last_input_at.reset();
      health_.last_good = now;
    }
    state_ = DpState::data_exchange;
    state_since_ = now;
    return;
  }
  if (state_ == DpState::diag_cyclic || d.prm_req) {
    restart(now, "slave left data exchange (diagnosis shows it not ready)");
    return;
  }
  // Still not ready (e.g. Stat_Diag): ask again one period later, for at most lost_slave_time.
  if (now - state_since_ > config_.lost_slave_time) {
    restart(now, "slave not ready within lost_slave_time");
    return;
  }
  next_cycle_at_ = now + std::max(config_.data_exchange_period, tsyn_);
}

void DpMaster::refuse(StartupFault::Kind kind) {
  startup_fault_.kind = kind;
  startup_fault_.diagnosis = diagnosis_;
  lifecycle_ = link::Lifecycle::fault;
  state_ = DpState::refused;
  const StandardDiag& d = diagnosis_.standard;
  const DiagText diag = describe(d);
  switch (kind) {
    case StartupFault::Kind::prm_fault:
      link::assign_formatted(
          fault_reason_, "slave refused the parameters (Set_Prm): Prm_Fault; its diagnosis: {}", diag.view());
      return;
    case StartupFault::Kind::cfg_fault:
      link::assign_formatted(fault_reason_,
                             "slave refused the configuration (Chk_Cfg): Cfg_Fault; its diagnosis: {}",
                             diag.view());
      return;
    case StartupFault::Kind::not_supported:
      link::assign_formatted(
          fault_reason_,
          "slave refused the parameters: a requested function (Freeze/Sync) is Not_Supported; "
          "its diagnosis: {}",
          diag.view());
      return;
    case StartupFault::Kind::rejected:
      link::assign_formatted(
          fault_reason_,
          "slave rejected Set_Prm (RS: service not activated for master {}); its diagnosis: {}",
          config_.master_address, diag.view());
      return;
    case StartupFault::Kind::ident_mismatch:
      link::assign_formatted(fault_reason_,
                             "our master refused the slave: ident number 0x{:04X}, configured 0x{:04X}; its "
                             "diagnosis: {}",
                             d.ident, setup_.ident, diag.view());
      return;
    case StartupFault::Kind::master_lock:
      link::assign_formatted(
          fault_reason_,
          "our master refused to take the slave: it is locked by master {} (we are {}); its "
          "diagnosis: {}",
          d.master_address, config_.master_address, diag.view());
      return;
    case StartupFault::Kind::none:
      break;
  }
  fault_reason_.clear();
}

}  // namespace cellctl::profibus

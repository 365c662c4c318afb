#include "monitor/monitor.hpp"

#include <algorithm>
#include <cmath>

#include "link/clock.hpp"

namespace cellctl::monitor {
namespace {

constexpr std::size_t idx(Rule r) noexcept {
  return static_cast<std::size_t>(r);
}

// An axis may overshoot its travel limit by this much before it counts as outside (encoder noise,
// the last edge of a soft stop); anything beyond is a fault.
constexpr double kPositionMarginMm = 0.5;

}  // namespace

Monitor::Monitor(const config::CellCore& cell) : cell_(cell) {}

StopCategory Monitor::category_of(Rule r) const noexcept {
  switch (rule_info(r).stop) {
    case StopClass::emergency:
      return StopCategory::immediate;
    case StopClass::operator_stop:
      return cell_.stops.operator_stop;
    case StopClass::link:
      return cell_.stops.link;
    case StopClass::following_error:
      return cell_.stops.following_error;
    case StopClass::fault:
      return cell_.stops.fault;
  }
  return StopCategory::immediate;  // (not reached: every class is named above)
}

void Monitor::check(const cell::CellState& s, const OperatorInputs& in,
                    std::array<std::optional<journal::Text>, kRuleCount>& causes) const noexcept {
  using journal::Text;
  if (in.emergency_stop) causes[idx(Rule::emergency_stop)] = Text::format("emergency stop requested");
  if (in.stop) causes[idx(Rule::operator_stop)] = Text::format("operator stop requested");
  if (!armed_) return;

  // A link that failed is named as the link; the measurements it carried are stale and not judged
  // (no "disagreement" or "following error" of a position that simply stopped arriving).
  std::array<bool, cell::kMaxDevices> fresh{};
  for (std::size_t d = 0; d < cell::kMaxDevices; ++d) {
    const auto& l = s.links[d];
    const auto name = s.devices[d];
    const double silent_ms = link::to_milliseconds(l.silent_for);
    fresh[d] = l.active && !l.fault && silent_ms <= cell_.limits.link_silence_ms;
    if (l.fault || !l.active)
      causes[idx(Rule::link_silent)] = Text::format("{} link lost (session {}), no good reply for {:.0f} ms",
                                                    name, l.fault ? "fault" : "inactive", silent_ms);
    else if (silent_ms > cell_.limits.link_silence_ms)
      causes[idx(Rule::link_silent)] = Text::format("{} silent for {:.0f} ms (limit {:.0f} ms)", name,
                                                    silent_ms, cell_.limits.link_silence_ms);
  }
  const bool scu_fresh = fresh[static_cast<std::size_t>(cell::Device::scu)];
  const bool encoder_fresh =
      fresh[static_cast<std::size_t>(cell::Device::encoder)] && s.encoder.data_exchange && s.encoder.ready;

  for (std::size_t i = 0; i < s.axis_count && i < cell_.axes.size(); ++i) {
    const auto& a = s.axes[i];
    const auto& c = cell_.axes[i];
    const double p = a.position_mm();
    // The position judged is the encoder's where it measures the axis, else the SCU's.
    const bool position_fresh = a.measured ? encoder_fresh : scu_fresh;
    if (position_fresh && (p < c.min_mm - kPositionMarginMm || p > c.max_mm + kPositionMarginMm))
      causes[idx(Rule::position_limit)] =
          Text::format("axis {} at {:.2f} mm, outside [{:g}, {:g}] mm", c.name, p, c.min_mm, c.max_mm);
    if (a.measured && encoder_fresh) {
      if (std::abs(a.encoder_mm_s) > cell_.limits.overspeed_mm_s)
        causes[idx(Rule::overspeed)] = Text::format("axis {} at {:.1f} mm/s by the encoder (limit {:g} mm/s)",
                                                    c.name, a.encoder_mm_s, cell_.limits.overspeed_mm_s);
      // The SCU's position is as old as its last RC reply (up to a keep-alive period), the encoder's is
      // fresh: what the axis travelled meanwhile is no disagreement. Right after each reply the
      // allowance is back to nothing, so a real one is caught within a keep-alive period.
      const double travelled = std::abs(a.encoder_mm_s) * link::to_seconds(s.scu_position_age);
      if (scu_fresh && std::abs(a.scu_mm - a.encoder_mm) > cell_.limits.disagreement_mm + travelled)
        causes[idx(Rule::disagreement)] =
            Text::format("axis {}: SCU {:.2f} mm, encoder {:.2f} mm (tolerance {:g} mm)", c.name, a.scu_mm,
                         a.encoder_mm, cell_.limits.disagreement_mm);
    }
    const auto& plan = planned_[i];
    if (following_ && plan.move && position_fresh) {
      // An axis the encoder does not measure is known by the SCU's position, as old as its last RC
      // reply: what the plan moved on meanwhile is no error.
      const double stale =
          a.measured ? 0.0 : std::abs(plan.planned_mm_s) * link::to_seconds(s.scu_position_age);
      const double allowed = config::allowed_following_error(c, plan.planned_mm_s);
      const double error = std::abs(plan.planned_mm - p);
      if (error > allowed + stale)
        causes[idx(Rule::following_error)] = Text::format(
            "axis {} at {:.2f} mm, planned {:.2f} mm: following error {:.2f} mm > {:.2f} mm allowed at "
            "{:.1f} mm/s",
            c.name, p, plan.planned_mm, error, allowed, std::abs(plan.planned_mm_s));
    }
  }

  const auto& e = s.encoder;
  if (!e.data_exchange || !e.ready)
    causes[idx(Rule::encoder_not_ready)] =
        Text::format("encoder {}", e.data_exchange ? "dropped its Ready bit" : "left data exchange");
  if (e.alarm) causes[idx(Rule::encoder_alarm)] = Text::format("encoder diagnosis reports an alarm");
  if (e.limit_switch)
    causes[idx(Rule::encoder_limit_switch)] = Text::format("encoder limit switch at {:.2f} mm", e.mm);
  if (e.diagnosis_pending)
    causes[idx(Rule::encoder_diagnosis)] = Text::format("encoder signals new diagnosis");

  const auto& sp = s.spindle;
  if (sp.fault)
    causes[idx(Rule::spindle_fault)] = Text::format("spindle converter fault {}", sp.fault_number);
  if (sp.over_temperature)
    causes[idx(Rule::spindle_temperature)] = Text::format("spindle motor over-temperature (PTC)");
  const double f = std::abs(sp.actual_hz);
  const double tol = cell_.limits.spindle_tolerance_hz;
  if (f > cell_.limits.spindle_max_hz + tol)
    causes[idx(Rule::spindle_frequency)] =
        Text::format("spindle at {:.0f} Hz, above the cell's {:g} Hz", f, cell_.limits.spindle_max_hz);
  else if (spindle_running_ && sp.settled && std::abs(f - spindle_set_hz_) > tol)
    causes[idx(Rule::spindle_frequency)] =
        Text::format("spindle at {:.0f} Hz while set to {:.0f} Hz", f, spindle_set_hz_);

  if (s.scu_errors.any())
    causes[idx(Rule::scu_error)] =
        Text::format("SCU error bit {}: {} (word 0x{:08x})", s.scu_errors.first_bit, s.scu_errors.first_cause,
                     s.scu_errors.word);
}

std::bitset<kRuleCount> Monitor::evaluate(const cell::CellState& state, const OperatorInputs& inputs,
                                          double t) noexcept {
  std::array<std::optional<journal::Text>, kRuleCount> causes{};
  check(state, inputs, causes);
  std::bitset<kRuleCount> fresh;
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    if (!causes[i] || latches_[i].active) continue;
    latches_[i] = Latch{true, category_of(static_cast<Rule>(i)), t, *causes[i]};
    fresh.set(i);
  }
  return fresh;
}

std::optional<StopCategory> Monitor::demanded_stop() const noexcept {
  std::optional<StopCategory> strongest;
  for (const auto& l : latches_)
    if (l.active && (!strongest || l.category < *strongest)) strongest = l.category;
  return strongest;
}

bool Monitor::reset(const cell::CellState& state, const OperatorInputs& inputs) noexcept {
  std::array<std::optional<journal::Text>, kRuleCount> causes{};
  check(state, inputs, causes);
  bool clear = true;
  for (std::size_t i = 0; i < kRuleCount; ++i) {
    if (!latches_[i].active) continue;
    if (causes[i]) {
      clear = false;
      continue;
    }
    latches_[i].active = false;
  }
  return clear;
}

}  // namespace cellctl::monitor

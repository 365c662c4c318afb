#include "routines/teach_in.hpp"

#include <cmath>

namespace cellctl::routines {
namespace {

constexpr double kSwitchTimeoutS = 20.0;   // re-parameterisation: DP start-up again
constexpr double kCommandTimeoutS = 5.0;   // a handshake: a few Data_Exchange cycles
constexpr double kHaltTimeoutS = 10.0;     // axes still after a halt
constexpr double kDevicesTimeoutS = 20.0;  // devices up at the start

recipe::Limits limits_for(const config::CellCore& cell, const TeachInRequest& r) {
  recipe::Limits l;
  l.axes.resize(cell.axes.size());
  if (r.axis >= 0 && static_cast<std::size_t>(r.axis) < cell.axes.size()) {
    const auto& a = cell.axes[static_cast<std::size_t>(r.axis)];
    l.axes[static_cast<std::size_t>(r.axis)] =
        recipe::AxisLimits{a.min_mm, a.max_mm, std::min(r.speed_mm_s, a.max_speed_mm_s), r.tolerance_mm};
    // The longest move at the routine's speed, with room for ramps and corrections.
    l.move_timeout_s = (a.max_mm - a.min_mm) / std::max(r.speed_mm_s, 1e-3) * 2.0 + 10.0;
  }
  return l;
}

}  // namespace

std::string_view to_string(TeachInPhase p) noexcept {
  switch (p) {
    case TeachInPhase::checking:
      return "checking";
    case TeachInPhase::to_start:
      return "moving to the start";
    case TeachInPhase::switching:
      return "switching the encoder to Teach-In";
    case TeachInPhase::starting:
      return "starting Teach-In";
    case TeachInPhase::travelling:
      return "travelling";
    case TeachInPhase::ending:
      return "ending Teach-In";
    case TeachInPhase::switching_taught:
      return "switching the encoder to the taught resolution";
    case TeachInPhase::returning:
      return "moving back";
    case TeachInPhase::verifying:
      return "verifying";
    case TeachInPhase::done:
      return "done";
    case TeachInPhase::halting:
      return "halting";
    case TeachInPhase::restoring:
      return "restoring the encoder's parameters";
    case TeachInPhase::failed:
      return "failed";
  }
  return "?";
}

TeachIn::TeachIn(const config::CellCore& cell, TeachInPort& port, const TeachInRequest& request, double dt)
    : cell_(cell),
      port_(port),
      request_(request),
      limits_(limits_for(cell, request)),
      executor_(cell, limits_, dt) {}

void TeachIn::enter(TeachInPhase p, double t) noexcept {
  phase_ = p;
  phase_since_ = t;
  confirmed_ = false;
  prompt_ = {};
}

void TeachIn::fail(double t, const journal::Text& why) noexcept {
  if (phase_ == TeachInPhase::halting || phase_ == TeachInPhase::restoring || phase_ == TeachInPhase::failed)
    return;
  failure_ = why;
  move_active_ = false;
  intents_.axes = {};
  intents_.halt = cell::Halt::controlled;
  enter(TeachInPhase::halting, t);
}

void TeachIn::abort(double t) {
  fail(t, journal::Text::format("aborted by the operator in phase '{}'", to_string(phase_)));
}

void TeachIn::fail_after(double t, double limit_s, const char* what) {
  if (t - phase_since_ > limit_s) fail(t, journal::Text::format("{} not done within {:g} s", what, limit_s));
}

void TeachIn::adjust(cell::CellState& s) const noexcept {
  if (request_.axis < 0 || request_.axis >= s.axis_count) return;
  s.axes[static_cast<std::size_t>(request_.axis)].measured = false;
  s.encoder.ready = s.encoder.data_exchange;
}

bool TeachIn::moving() const noexcept {
  return move_active_ || phase_ == TeachInPhase::halting;
}

void TeachIn::start_move(const cell::CellState& s, double target_mm, double t) {
  recipe::Move m;
  m.targets.push_back({request_.axis, target_mm});
  m.speed_mm_s = request_.speed_mm_s;
  executor_.start(m, s, t, move_id_);
  move_active_ = true;
}

std::optional<bool> TeachIn::step_move(const cell::CellState& s, double t) {
  const auto status = executor_.step(s, t, intents_, move_id_);
  if (status == motion::MoveStatus::running) return std::nullopt;
  move_active_ = false;
  intents_.axes = {};
  if (status == motion::MoveStatus::done) return true;
  fail(t, executor_.reason());
  return false;
}

void TeachIn::step_checking(const cell::CellState& s, double t) {
  const auto a = static_cast<std::size_t>(request_.axis);
  if (request_.axis < 0 || a >= cell_.axes.size() || !cell_.axes[a].encoder) {
    fail(t, journal::Text::format("the encoder does not measure this axis"));
    return;
  }
  if (const auto why = port_.unavailable(); !why.empty()) {
    fail(t, journal::Text::format("{}", why));
    return;
  }
  const auto& c = cell_.axes[a];
  const auto enc = port_.read();
  if (!enc.failure.empty()) {
    fail(t, journal::Text::format("encoder: {}", enc.failure));
    return;
  }
  if (!(s.scu_remote && s.axes[a].present && enc.up)) {
    fail_after(t, kDevicesTimeoutS, "devices up (SCU remote mode, encoder in data exchange and ready)");
    return;
  }
  if (enc.stored_offset != 0) {
    fail(t, journal::Text::format(
                "the encoder holds preset offset {}: Teach-In runs with offset 0 and leaves it 0 (manual "
                "4.4.2.1), which would move every position. Preset the encoder back to offset 0 first, and "
                "use zero_offset_mm in the config for the axis zero",
                enc.stored_offset));
    return;
  }
  start_mm_ = request_.from_mm.value_or(s.axes[a].scu_mm);
  const double end_mm = start_mm_ + request_.distance_mm;
  if (request_.distance_mm <= 0.0 || start_mm_ < c.min_mm || end_mm > c.max_mm) {
    fail(t, journal::Text::format("the travel {:.2f} … {:.2f} mm is not within axis {}'s [{:g}, {:g}] mm",
                                  start_mm_, end_mm, c.name, c.min_mm, c.max_mm));
    return;
  }
  if (!request_.manual && std::abs(s.axes[a].scu_mm - start_mm_) > request_.tolerance_mm) {
    start_move(s, start_mm_, t);
    enter(TeachInPhase::to_start, t);
    return;
  }
  if (request_.manual && std::abs(s.axes[a].scu_mm - start_mm_) > request_.tolerance_mm && !confirmed_) {
    prompt_ = journal::Text::format("move axis {} to the start, {:.2f} mm, and confirm", c.name, start_mm_);
    return;
  }
  port_.switch_to(EncoderSetting::teach_in, s.now);
  switched_ = true;
  enter(TeachInPhase::switching, t);
}

void TeachIn::step(const cell::CellState& s, std::optional<config::StopCategory> demanded,
                   std::string_view stop_reason, double t) {
  if (demanded && !finished() && phase_ != TeachInPhase::halting && phase_ != TeachInPhase::restoring)
    fail(t, journal::Text::format("stopped by the monitor: {}", stop_reason));
  if (demanded && *demanded == config::StopCategory::immediate) intents_.halt = cell::Halt::immediate;
  const auto a = static_cast<std::size_t>(std::max(request_.axis, 0));
  const auto& axis = s.axes[a];
  const auto enc = port_.read();
  switch (phase_) {
    case TeachInPhase::checking:
      step_checking(s, t);
      break;
    case TeachInPhase::to_start:
      if (auto r = step_move(s, t); r && *r) {
        port_.switch_to(EncoderSetting::teach_in, s.now);
        switched_ = true;
        enter(TeachInPhase::switching, t);
      }
      break;
    case TeachInPhase::switching:
      if (enc.up && !enc.teach_in_running) {
        if (!port_.start_teach_in()) {
          fail(t, journal::Text::format("the encoder session would not start Teach-In"));
          break;
        }
        enter(TeachInPhase::starting, t);
      } else if (!enc.failure.empty() && t > phase_since_) {
        fail(t, journal::Text::format("switching the encoder: {}", enc.failure));
      } else {
        fail_after(t, kSwitchTimeoutS, "the encoder's start-up with the Teach-In parameters");
      }
      break;
    case TeachInPhase::starting: {
      if (enc.command == EncoderCommand::failed) {
        fail(t, journal::Text::format("Teach-In start: {}", enc.failure));
        break;
      }
      if (enc.command != EncoderCommand::done) {
        fail_after(t, kCommandTimeoutS, "the encoder's acknowledge of Teach-In start");
        break;
      }
      port_.clear_command();
      // 4.4.2.1: the native zero must not be crossed. Counts rise with the axis (+), so the travel
      // covers native positions n0 … n0 + distance (plus the margin and a 2 % scale allowance).
      const double n0 = enc.position_mm;
      const double lo = n0 - request_.native_zero_margin_mm;
      const double hi = n0 + request_.distance_mm * 1.02 + request_.native_zero_margin_mm;
      if (lo <= 0.0 && hi >= 0.0) {
        fail(t, journal::Text::format(
                    // Fits journal::Text's 160 octets with the widest numbers a travel gives.
                    "encoder native zero at {} {:.2f} mm, inside the travel {:.2f} to {:.2f} mm (margin "
                    "{:g}): must "
                    "not be crossed (manual 4.4.2.1); start at {:.1f} mm or above",
                    cell_.axes[a].name, axis.scu_mm - n0, axis.scu_mm, axis.scu_mm + request_.distance_mm,
                    request_.native_zero_margin_mm, axis.scu_mm - n0 + request_.native_zero_margin_mm + 0.5));
        break;
      }
      scu_at_start_ = axis.scu_mm;
      native_last_mm_ = n0;
      enter(TeachInPhase::travelling, t);
      if (request_.manual)
        prompt_ =
            journal::Text::format("Teach-In started: move axis {} by {:.3f} mm in + direction and confirm",
                                  cell_.axes[a].name, request_.distance_mm);
      else
        start_move(s, scu_at_start_ + request_.distance_mm, t);
      break;
    }
    case TeachInPhase::travelling: {
      // A jump of more than half the physical range between two cycles is the native zero crossed.
      if (std::abs(enc.position_mm - native_last_mm_) > enc.native_range_mm / 2.0) {
        fail(t, journal::Text::format(
                    "the axis crossed the encoder's native zero during Teach-In (manual 4.4.2.1)"));
        break;
      }
      native_last_mm_ = enc.position_mm;
      const bool arrived = request_.manual ? confirmed_ : step_move(s, t).value_or(false);
      if (!arrived || finished() || phase_ == TeachInPhase::halting) break;
      scu_at_end_ = axis.scu_mm;
      result_.scu_distance_mm = request_.manual ? request_.distance_mm : scu_at_end_ - scu_at_start_;
      if (!port_.end_teach_in(result_.scu_distance_mm)) {
        fail(t, journal::Text::format("the encoder session would not end Teach-In"));
        break;
      }
      enter(TeachInPhase::ending, t);
      break;
    }
    case TeachInPhase::ending:
      if (enc.command == EncoderCommand::failed) {
        fail(t, journal::Text::format("Teach-In end: {}", enc.failure));
      } else if (enc.command == EncoderCommand::done) {
        result_.total_resolution = enc.total_resolution;
        port_.clear_command();
        port_.switch_to(EncoderSetting::taught, s.now);
        enter(TeachInPhase::switching_taught, t);
      } else {
        fail_after(t, kCommandTimeoutS, "the encoder's total resolution (Teach-In end)");
      }
      break;
    case TeachInPhase::switching_taught:
      if (enc.up && !enc.teach_in_running) {
        encoder_at_end_ = enc.position_mm;
        scu_at_end_ = axis.scu_mm;
        enter(TeachInPhase::returning, t);
        if (request_.manual)
          prompt_ = journal::Text::format("move axis {} back to the start mark ({:.3f} mm back) and confirm",
                                          cell_.axes[a].name, request_.distance_mm);
        else
          start_move(s, scu_at_start_, t);
      } else {
        fail_after(t, kSwitchTimeoutS, "the encoder's start-up with the taught resolution");
      }
      break;
    case TeachInPhase::returning:
      if (request_.manual ? confirmed_ : step_move(s, t).value_or(false)) enter(TeachInPhase::verifying, t);
      break;
    case TeachInPhase::verifying: {
      // One cycle later: the encoder's input is from after the stop.
      if (t - phase_since_ < 0.1) break;
      result_.encoder_distance_mm = encoder_at_end_ - enc.position_mm;
      result_.scu_back_mm = request_.manual ? request_.distance_mm : scu_at_end_ - axis.scu_mm;
      const double diff = result_.encoder_distance_mm - result_.scu_back_mm;
      if (!enc.up || std::abs(diff) > request_.tolerance_mm) {
        fail(t,
             journal::Text::format(
                 "verification failed: moving back, the taught encoder measured {:.4f} mm, the {} {:.4f} mm "
                 "(difference {:.4f} mm, tolerance {:g} mm)",
                 result_.encoder_distance_mm, request_.manual ? "distance given" : "SCU", result_.scu_back_mm,
                 diff, request_.tolerance_mm));
        break;
      }
      enter(TeachInPhase::done, t);
      break;
    }
    case TeachInPhase::halting:
      intents_.axes = {};
      if ((!axis.moving && !axis.commanded) || t - phase_since_ > kHaltTimeoutS) {
        if (switched_) {
          port_.switch_to(EncoderSetting::configured, s.now);
          enter(TeachInPhase::restoring, t);
        } else {
          enter(TeachInPhase::failed, t);
        }
      }
      break;
    case TeachInPhase::restoring:
      if (enc.up && !enc.teach_in_running) {
        switched_ = false;
        enter(TeachInPhase::failed, t);
      } else if (t - phase_since_ > kSwitchTimeoutS) {
        enter(TeachInPhase::failed, t);  // switched_ stays: the caller says the restore is unconfirmed
      }
      break;
    case TeachInPhase::done:
    case TeachInPhase::failed:
      break;
  }
}

}  // namespace cellctl::routines

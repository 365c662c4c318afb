// scu::Session: the commands the controller gives it — move, stop, emergency stop and its release, speed,
// read — each checked and queued, answered with a typed CommandResult.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "scu/data_list.hpp"
#include "scu/session.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::scu {

void Session::drop_queued_moves(std::optional<std::uint8_t> function) {
  (void)normal_.remove_if([&](const Pending& p) {  // how many: no matter
    const bool move =
        p.purpose == Purpose::position || p.purpose == Purpose::speed || p.purpose == Purpose::execute;
    return move && (!function || p.function == *function);
  });
  for (std::size_t f = 0; f < kMotionFunctionCount; ++f) {
    if (function && f != *function) continue;
    if (snapshot_.functions[f].outcome == MoveOutcome::queued)
      snapshot_.functions[f].outcome = MoveOutcome::stopped_short;
  }
}

std::uint16_t Session::percent(int function, double speed_mm_s) const noexcept {
  const auto& fn = config_.functions[static_cast<std::size_t>(function - 1)];
  double full = 0.0;
  for (std::size_t a = 0; a < kActuatorCount; ++a)
    if (fn.actuators.test(a)) full = std::max(full, config_.specs[a].full_speed_mm_s);
  if (!(full > 0.0) || !std::isfinite(speed_mm_s)) return 1;
  return static_cast<std::uint16_t>(std::clamp(std::lround(100.0 * speed_mm_s / full), 1L, 100L));
}

bool Session::on_its_way(Purpose p) const noexcept {
  return (in_flight_ && in_flight_->purpose == p) ||
         urgent_.any([&](const Pending& q) { return q.purpose == p; });
}

CommandResult Session::move_to(int function, std::span<const ActuatorTarget> targets, double speed_mm_s,
                               bool soft) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  if (!(speed_mm_s > 0.0)) return {CommandStatus::bad_speed};
  if (snapshot_.emergency_stop_open) return {CommandStatus::emergency_stop_holds};
  const auto speed_percent = percent(function, speed_mm_s);
  const auto f = static_cast<std::size_t>(function - 1);
  auto& fs = snapshot_.functions[f];
  if (fs.execution_open || stop_queued_.test(f) || fs.outcome == MoveOutcome::queued)
    return {CommandStatus::function_busy};
  const auto& fn = config_.functions[f];
  std::bitset<kActuatorCount> given;
  for (const auto& t : targets) {
    if (!fn.moves(t.actuator)) return {CommandStatus::wrong_actuators};
    given.set(static_cast<std::size_t>(t.actuator - 1));
  }
  if (given != fn.actuators) return {CommandStatus::wrong_actuators};
  if (normal_.free_space() < targets.size() + 2) return {CommandStatus::queue_full};
  std::array<std::int32_t, kActuatorCount> edges{};
  for (const auto& t : targets) {
    const auto a = static_cast<std::size_t>(t.actuator - 1);
    const double e = std::round(t.mm * config_.specs[a].edges_per_mm);
    if (!std::isfinite(e) || std::abs(e) > 2e9) return {CommandStatus::target_out_of_range};
    edges[a] = static_cast<std::int32_t>(e);
  }
  // Room for every telegram was checked above: none of these pushes fails.
  for (const auto& t : targets) {
    const auto a = static_cast<std::size_t>(t.actuator - 1);
    fs.targets[a] = edges[a];
    std::array<std::uint8_t, 4> value{};
    wire::ByteWriter w(value);
    w.le(edges[a]);
    (void)enqueue(false, TransferRequest{data_id::remote_position(t.actuator), value}, Purpose::position,
                  fnc(function));
  }
  std::array<std::uint8_t, 2> speed{};
  wire::ByteWriter w(speed);
  w.le(speed_percent);
  (void)enqueue(false, TransferRequest{data_id::remote_speed(function), speed}, Purpose::speed,
                fnc(function));
  (void)enqueue(false,
                ExecuteRequest{fnc(function), static_cast<std::uint8_t>(Direction::remote_position),
                               soft ? kSoftStartStop : kFastStartStop},
                Purpose::execute, fnc(function));
  fs.targeted = given;
  fs.speed_percent = speed_percent;
  fs.outcome = MoveOutcome::queued;
  return {};
}

CommandResult Session::stop(int function, bool soft) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  const auto f = static_cast<std::size_t>(function - 1);
  drop_queued_moves(fnc(function));
  const StopRequest rs{fnc(function), soft ? kSoftStartStop : kFastStartStop};
  // Asked again while its RS still waits, the RS keeps its place (only its mode may change): a stop
  // asked again every cycle must not fall behind what was queued meanwhile, such as a re-sent F20.
  if (auto* queued = urgent_.find_if(
          [&](const Pending& p) { return p.purpose == Purpose::stop && p.function == fnc(function); })) {
    // An RS always fits its buffer (it fitted when it was queued).
    (void)encode_request(rs, queued->bytes);
    stop_queued_.set(f);
    return {};
  }
  if (!enqueue(true, rs, Purpose::stop, fnc(function))) return {CommandStatus::queue_full};
  stop_queued_.set(f);
  return {};
}

CommandResult Session::emergency_stop() {
  if (lifecycle() != link::Lifecycle::active && lifecycle() != link::Lifecycle::deactivating)
    return {CommandStatus::not_active};
  drop_queued_moves(std::nullopt);
  if (on_its_way(Purpose::emergency_stop)) return {};  // one F20 until the SCU has answered it
  Pending p;
  const ExecuteRequest f20{kEmergencyStopFnc, kUnusedParam, kUnusedParam};
  (void)encode_request(f20, p.bytes);  // an RE always fits its buffer
  p.shape = reply_shape(f20);
  p.purpose = Purpose::emergency_stop;
  // The first F20 goes ahead of everything. One asked for again after the SCU refused it waits behind
  // the stops queued meanwhile: an SCU that keeps refusing F20 must not starve each axis's own stop.
  const bool queued = f20_refused_ ? urgent_.push_back(p) : urgent_.push_front(p);
  return {queued ? CommandStatus::taken : CommandStatus::queue_full};
}

CommandResult Session::release_emergency_stop() {
  if (!accepting()) return {CommandStatus::not_active};
  if (!snapshot_.emergency_stop_open) return {CommandStatus::no_emergency_stop};
  // Asked every cycle until the SCU has answered: one RS goes out, not one per cycle.
  if (on_its_way(Purpose::release_emergency)) return {};
  if (!enqueue(true, StopRequest{kEmergencyStopFnc, kUnusedParam}, Purpose::release_emergency))
    return {CommandStatus::queue_full};
  return {};
}

CommandResult Session::set_speed(int function, double speed_mm_s) {
  if (!accepting()) return {CommandStatus::not_active};
  if (!defined(function)) return {CommandStatus::unknown_function};
  if (!(speed_mm_s > 0.0)) return {CommandStatus::bad_speed};
  const auto speed_percent = percent(function, speed_mm_s);
  if (snapshot_.functions[static_cast<std::size_t>(function - 1)].speed_percent == speed_percent) return {};
  std::array<std::uint8_t, 2> speed{};
  wire::ByteWriter w(speed);
  w.le(speed_percent);
  if (!enqueue(false, TransferRequest{data_id::remote_speed(function), speed}, Purpose::speed, fnc(function)))
    return {CommandStatus::queue_full};
  snapshot_.functions[static_cast<std::size_t>(function - 1)].speed_percent = speed_percent;
  return {};
}

CommandResult Session::read(std::uint16_t data_id) {
  if (!accepting()) return {CommandStatus::not_active};
  if (value_size(data_id) == 0 || value_size(data_id) > kMaxReplyData)
    return {CommandStatus::unknown_data_id};
  if (!enqueue(false, GetRequest{data_id}, Purpose::read, 0, data_id)) return {CommandStatus::queue_full};
  return {};
}

}  // namespace cellctl::scu

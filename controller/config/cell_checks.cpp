#include "config/cell_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "config/cell_config.hpp"
#include "encoder/cyclic.hpp"
#include "encoder/scaling.hpp"
#include "link/clock.hpp"

namespace cellctl::config {
namespace {

using link::to_milliseconds;

// The monitor takes a link silent longer than limits.link_silence_ms for a lost device (category 0):
// a healthy device's replies must come closer together than that, or the cell stops mid-run.
// `spacing` says how the device's longest normal gap between good replies, `gap_ms`, is made up.
void check_reply_spacing(const YamlNode& root, const CellConfig& cell, const char* device, double gap_ms,
                         const std::string& spacing) {
  const double silence_ms = cell.limits.link_silence_ms;
  if (silence_ms > gap_ms) return;
  const auto limits = root.maybe("limits");
  if (limits && limits->has("link_silence_ms"))
    limits->at("link_silence_ms")
        .fail(fmt::format("{:g} ms must exceed the {}'s normal reply spacing ({}): a healthy {} would be "
                          "taken for a silent link",
                          silence_ms, device, spacing, device));
  // Not given, the default applies: the device's section is where the too-long timing was chosen.
  root.at(device).fail(fmt::format(
      "the normal reply spacing ({}) must be shorter than limits.link_silence_ms ({:g} ms, the default): a "
      "healthy {} would be taken for a silent link",
      spacing, silence_ms, device));
}

void check_link_silence(const YamlNode& root, const CellConfig& cell) {
  if (cell.scu) {
    const auto& s = cell.scu->session;
    const double gap = to_milliseconds(s.keepalive_period) + to_milliseconds(s.reply_timeout);
    check_reply_spacing(
        root, cell, "scu", gap,
        fmt::format("keep-alive {:g} ms + reply time-out {:g} ms = {:g} ms",
                    to_milliseconds(s.keepalive_period), to_milliseconds(s.reply_timeout), gap));
  }
  if (cell.spindle) {
    const auto& s = cell.spindle->session;
    const double gap = to_milliseconds(s.status_poll) + to_milliseconds(s.reply_timeout);
    check_reply_spacing(root, cell, "spindle", gap,
                        fmt::format("status poll {:g} ms + reply time-out {:g} ms = {:g} ms",
                                    to_milliseconds(s.status_poll), to_milliseconds(s.reply_timeout), gap));
  }
  if (cell.encoder) {
    const double lost_ms = to_milliseconds(cell.encoder->session.bus.lost_slave_time);
    check_reply_spacing(root, cell, "encoder", lost_ms, fmt::format("DP lost-slave time {:g} ms", lost_ms));
  }
}

constexpr std::pair<encoder::TimeBase, const char*> kTimeBases[] = {
    {encoder::TimeBase::steps_per_s, "steps_per_s"},
    {encoder::TimeBase::steps_per_100ms, "steps_per_100ms"},
    {encoder::TimeBase::steps_per_10ms, "steps_per_10ms"},
    {encoder::TimeBase::rpm, "rpm"},
};

// The encoder's velocity (Scancon 2.2/3.0) and acceleration (3.0) are signed 16-bit values in the time
// base's unit that saturate at 32767 (manual 4.3.4/4.3.5): a time base in which the overspeed limit
// (or the measured axis's acceleration) reaches 32767 would show an overspeed as a smaller, saturated
// speed, and the monitor would never see it. Refused, with the numbers and the time bases that fit.
void check_encoder_time_base(const YamlNode& root, const CellConfig& cell) {
  if (!cell.encoder) return;
  const auto& s = cell.encoder->session;
  const auto f = s.parameters.functionality;
  if (f != encoder::Functionality::scancon22 && f != encoder::Functionality::scancon30) return;
  const encoder::Scaling scaling(s.parameters, s.physical);
  const double per_mm = encoder::units_per_mm(s.counts_per_mm, s.mm_per_revolution, scaling);
  const double per_rev = scaling.units_per_revolution();
  double accel_mm_s2 = 0.0;
  for (const auto& axis : cell.axes)
    if (axis.encoder) accel_mm_s2 = axis.max_accel_mm_s2;
  // What the encoder reports at the overspeed limit, and one sample period's change of it at the
  // axis's acceleration, in the time base tb.
  const auto velocity = [&](encoder::TimeBase tb) {
    return encoder::in_time_base(cell.limits.overspeed_mm_s * per_mm, tb, per_rev);
  };
  const auto acceleration = [&](encoder::TimeBase tb) {
    return f == encoder::Functionality::scancon30 ? encoder::in_time_base(accel_mm_s2 * per_mm, tb, per_rev) *
                                                        link::to_seconds(encoder::sample_period(tb))
                                                  : 0.0;
  };
  constexpr double kFull = 32767.0;
  const auto fits = [&](encoder::TimeBase tb) { return velocity(tb) < kFull && acceleration(tb) < kFull; };
  const encoder::TimeBase tb = s.parameters.time_base;
  if (fits(tb)) return;
  std::string choices;
  for (const auto& [other, name] : kTimeBases)
    if (fits(other))
      choices += fmt::format("{}{} ({:.0f})", choices.empty() ? "" : ", ", name, velocity(other));
  const char* chosen = "steps_per_s";
  for (const auto& [other, name] : kTimeBases)
    if (other == tb) chosen = name;
  const std::string what =
      velocity(tb) >= kFull
          ? fmt::format("the overspeed limit {:g} mm/s is {:.0f} units/s = {:.0f} in {}",
                        cell.limits.overspeed_mm_s, cell.limits.overspeed_mm_s * per_mm, velocity(tb), chosen)
          : fmt::format("axis acceleration {:g} mm/s² changes the velocity by {:.0f} per {} sample",
                        accel_mm_s2, acceleration(tb), chosen);
  const std::string rule = fmt::format(
      "{}, beyond the encoder's 16-bit {} (at most 32767, manual 4.3.4/4.3.5): it would saturate and an "
      "overspeed would go unseen; {}",
      what, velocity(tb) >= kFull ? "velocity" : "acceleration",
      choices.empty() ? "no time base fits: lower limits.overspeed_mm_s or scale the encoder"
                      : "time bases that fit (value at the limit): " + choices);
  const YamlNode section = root.at("encoder");
  if (section.has("time_base")) section.at("time_base").fail(rule);
  section.fail("time_base steps_per_s (the default): " + rule);
}

}  // namespace

void check_cell(const YamlNode& root, CellConfig& cell) {
  const auto axes = root.at("axes").items();
  bool measured = false;
  for (std::size_t i = 0; i < cell.axes.size(); ++i) {
    auto& axis = cell.axes[i];
    const auto& node = axes[i];
    measured = measured || axis.encoder;
    if (!cell.scu) {
      if (axis.edges_per_mm <= 0.0) node.fail("edges_per_mm is needed when the cell has no scu section");
      axis.full_speed_mm_s = axis.max_speed_mm_s;
      continue;
    }
    const auto& scu = *cell.scu;
    const auto& act = scu.session.specs[static_cast<std::size_t>(axis.actuator - 1)];
    if (!scu.session.actuators.test(static_cast<std::size_t>(axis.actuator - 1)))
      node.at("actuator").fail(fmt::format("the scu section has no actuator {}", axis.actuator));
    const auto& fn = scu.session.functions[static_cast<std::size_t>(axis.function - 1)];
    if (!fn.defined)
      node.at("function").fail(fmt::format("the scu section has no function {}", axis.function));
    if (fn.actuators.count() != 1 || !fn.moves(axis.actuator))
      node.at("function")
          .fail(fmt::format("function {} must move actuator {} alone to drive axis '{}'", axis.function,
                            axis.actuator, axis.name));
    if (axis.edges_per_mm <= 0.0) {
      axis.edges_per_mm = act.edges_per_mm;
    } else if (std::abs(axis.edges_per_mm - act.edges_per_mm) > 1e-9) {
      node.at("edges_per_mm")
          .fail(fmt::format(
              "{:g} disagrees with the SCU's actuator {} ({:g}); state it once, in the scu section",
              axis.edges_per_mm, axis.actuator, act.edges_per_mm));
    }
    if (axis.max_mm > act.stroke_mm)
      node.at("max_mm").fail(fmt::format("{:g} mm is beyond actuator {}'s stroke of {:g} mm", axis.max_mm,
                                         axis.actuator, act.stroke_mm));
    axis.full_speed_mm_s = act.full_speed_mm_s;
    if (axis.max_speed_mm_s > axis.full_speed_mm_s)
      node.at("max_speed_mm_s")
          .fail(fmt::format("{:g} mm/s is beyond actuator {}'s full speed of {:g} mm/s", axis.max_speed_mm_s,
                            axis.actuator, axis.full_speed_mm_s));
    if (axis.min_mm < 0.0) node.at("min_mm").fail("an actuator's travel starts at 0 mm (fully in)");
  }
  if (cell.encoder && !measured)
    root.at("axes").fail("the cell has an encoder: mark the axis it measures with 'encoder: true'");
  if (!cell.encoder && measured)
    root.at("axes").fail("an axis is marked 'encoder: true' but the cell has no encoder section");
  check_link_silence(root, cell);
  check_encoder_time_base(root, cell);
}

}  // namespace cellctl::config

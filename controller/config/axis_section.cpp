#include "config/axis_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cellctl::config {

std::vector<AxisConfig> parse_axes(const YamlNode& list) {
  std::vector<AxisConfig> axes;
  const auto items = list.items();
  if (items.empty()) list.fail("the cell needs at least one axis");
  if (items.size() > 6) list.fail("the SCU drives at most 6 actuators");
  for (const auto& n : items) {
    n.only_keys({"name", "actuator", "function", "edges_per_mm", "min_mm", "max_mm", "max_speed_mm_s",
                 "min_speed_mm_s", "max_accel_mm_s2", "max_jerk_mm_s3", "encoder", "correct_in_motion",
                 "min_ferror_mm", "ferror_mm", "homing"});
    AxisConfig a;
    a.name = n.string_at("name");
    if (a.name.empty() ||
        !std::all_of(a.name.begin(), a.name.end(), [](char c) { return std::isalnum(c) || c == '_'; }))
      n.at("name").fail("an axis name is letters, digits and '_'");
    if (a.name.size() > kAxisNameMax)
      n.at("name").fail(fmt::format("an axis name has at most {} characters", kAxisNameMax));
    for (const auto& other : axes)
      if (other.name == a.name) n.at("name").fail(fmt::format("axis '{}' is defined twice", a.name));
    a.actuator = n.int_in<int>("actuator", 1, 6);
    for (const auto& other : axes)
      if (other.actuator == a.actuator)
        n.at("actuator")
            .fail(fmt::format("actuator {} already belongs to axis '{}'", a.actuator, other.name));
    a.function = n.int_in<int>("function", 1, 10);
    a.edges_per_mm = n.double_in_or("edges_per_mm", 0.001, 1e6, 0.0);  // 0: the SCU section's
    a.min_mm = n.at("min_mm").as_double();
    a.max_mm = n.at("max_mm").as_double();
    if (a.max_mm <= a.min_mm) n.at("max_mm").fail(fmt::format("must be above min_mm ({:g})", a.min_mm));
    a.max_speed_mm_s = n.double_in("max_speed_mm_s", 0.001, 1000.0);
    a.min_speed_mm_s = n.double_in_or("min_speed_mm_s", 0.0, a.max_speed_mm_s, 0.0);
    a.max_accel_mm_s2 = n.double_in_or("max_accel_mm_s2", 0.001, 1e5, a.max_accel_mm_s2);
    a.max_jerk_mm_s3 = n.double_in_or("max_jerk_mm_s3", 0.001, 1e7, a.max_jerk_mm_s3);
    a.encoder = n.bool_or("encoder", false);
    a.correct_in_motion = n.bool_or("correct_in_motion", false);
    if (a.correct_in_motion && !a.encoder)
      n.at("correct_in_motion").fail("a correction in motion needs the encoder on this axis (encoder: true)");
    a.min_ferror_mm = n.double_in_or("min_ferror_mm", 0.001, 1000.0, a.min_ferror_mm);
    a.ferror_mm = n.double_in_or("ferror_mm", 0.001, 1000.0, a.ferror_mm);
    if (a.ferror_mm < a.min_ferror_mm)
      (n.has("ferror_mm") ? n.at("ferror_mm") : n.at("min_ferror_mm"))
          .fail(fmt::format("ferror_mm ({:g}) must be at least min_ferror_mm ({:g})", a.ferror_mm,
                            a.min_ferror_mm));
    if (a.encoder)
      for (const auto& other : axes)
        if (other.encoder)
          n.at("encoder").fail(fmt::format("the encoder already measures axis '{}'", other.name));
    if (auto h = n.maybe("homing")) a.homing = parse_homing(*h, a);
    axes.push_back(std::move(a));
  }
  return axes;
}

double allowed_following_error(const AxisConfig& axis, double planned_mm_s) noexcept {
  const double scaled = axis.ferror_mm * std::abs(planned_mm_s) / axis.max_speed_mm_s;
  return std::clamp(scaled, axis.min_ferror_mm, axis.ferror_mm);
}

}  // namespace cellctl::config

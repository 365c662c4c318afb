#include "config/homing_section.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "config/axis_section.hpp"

namespace cellctl::config {

const char* to_string(HomingStrategy s) noexcept {
  switch (s) {
    case HomingStrategy::none:
      return "none";
    case HomingStrategy::absolute_encoder:
      return "absolute_encoder";
    case HomingStrategy::end_position:
      return "end_position";
    case HomingStrategy::scu_initialised:
      return "scu_initialised";
  }
  return "?";
}

HomingConfig parse_homing(const YamlNode& n, const AxisConfig& axis) {
  n.only_keys({"strategy", "sequence", "end", "speed_mm_s", "preset_mm", "home_mm", "tolerance_mm"});
  HomingConfig h;
  const auto strategy = n.at("strategy").as_choice({"absolute_encoder", "end_position", "scu_initialised"});
  h.strategy = strategy == "absolute_encoder" ? HomingStrategy::absolute_encoder
               : strategy == "end_position"   ? HomingStrategy::end_position
                                              : HomingStrategy::scu_initialised;
  h.sequence = n.int_in_or<int>("sequence", 0, 9, 0);
  h.tolerance_mm = n.double_in_or("tolerance_mm", 0.001, 100.0, h.tolerance_mm);
  const bool moves = h.strategy != HomingStrategy::absolute_encoder;
  if (h.strategy == HomingStrategy::absolute_encoder && !axis.encoder)
    n.at("strategy")
        .fail(fmt::format("absolute_encoder needs the encoder on axis '{}' (encoder: true)", axis.name));
  if (!moves) {
    for (const char* key : {"end", "speed_mm_s", "preset_mm", "home_mm"})
      if (n.has(key)) n.at(key).fail("absolute_encoder homing does not move the axis: remove it");
    return h;
  }
  if (auto e = n.maybe("end"))
    h.end =
        e->as_choice({"retracted", "extended"}) == "retracted" ? HomingEnd::retracted : HomingEnd::extended;
  const double fallback = std::min(axis.max_speed_mm_s, std::max(2.0, 2.0 * axis.min_speed_mm_s));
  h.speed_mm_s = n.double_in_or("speed_mm_s", axis.min_speed_mm_s * 1.2, axis.max_speed_mm_s, fallback);
  h.home_mm = n.double_in_or("home_mm", axis.min_mm, axis.max_mm,
                             h.end == HomingEnd::retracted ? axis.min_mm : axis.max_mm);
  if (n.has("preset_mm") && !(h.strategy == HomingStrategy::end_position && axis.encoder))
    n.at("preset_mm").fail("only end_position homing of the axis the encoder measures presets the encoder");
  h.preset_mm =
      n.double_in_or("preset_mm", 0.0, 1e6, h.end == HomingEnd::retracted ? axis.min_mm : axis.max_mm);
  return h;
}

}  // namespace cellctl::config

#include "web/cell_board.hpp"

#include <cmath>

namespace cellctl::web {
namespace {

// Positions to the µm the SCU and the encoder resolve at best; times to the ms.
double rounded(double v, double resolution) {
  return std::round(v / resolution) * resolution;
}

nlohmann::json position(bool known, double mm) {
  return known ? nlohmann::json(rounded(mm, 0.001)) : nlohmann::json();
}

const char* link_word(const status::StatusView& v, std::size_t d) {
  if (v.link_fault[d]) return "lost";
  return v.link_active[d] ? "up" : "down";
}

}  // namespace

nlohmann::json board_payload(const std::vector<std::string>& axis_names,
                             const std::optional<status::StatusView>& view, bool live) {
  nlohmann::json axes = nlohmann::json::array();
  nlohmann::json devices = nlohmann::json::array();
  for (std::size_t i = 0; i < axis_names.size(); ++i) {
    nlohmann::json a{{"name", axis_names[i]}};
    if (view && i < view->axes && i < cell::kMaxAxes) {
      const auto& v = *view;
      a["target_mm"] = position(v.target_known[i], v.target_mm[i]);
      a["scu_mm"] = position(v.position_known[i], v.scu_mm[i]);
      a["encoder_mm"] = position(v.encoder_measures[i], v.encoder_mm[i]);
      a["homed"] = {{"record", v.home_recorded[i]}, {"scu", v.scu_initialised[i]}};
    }
    axes.push_back(std::move(a));
  }
  if (view) {
    const auto& v = *view;
    for (std::size_t d = 0; d < v.devices.size(); ++d) {
      if (v.devices[d].empty()) continue;  // a slot without a device
      const auto& c = v.link_counts[d];
      devices.push_back({{"name", std::string(v.devices[d])},
                         {"link", link_word(v, d)},
                         {"round_trip_ms", rounded(v.link_round_trip_s[d] * 1e3, 0.1)},
                         {"last_good_s", rounded(v.link_silent_s[d], 0.001)},
                         {"replies", c.good_replies},
                         {"timeouts", c.timeouts},
                         {"bad_frames", c.bad_frames},
                         {"refusals", c.refusals}});
      // The run's own verdict once its stop has resolved the device (cellctl run has no run records).
      if (!v.safe[d].empty()) devices.back()["safe"] = std::string(v.safe[d]);
    }
  }
  nlohmann::json out{{"live", view && live}, {"axes", std::move(axes)}, {"devices", std::move(devices)}};
  if (view) {
    out["t"] = rounded(view->t, 0.001);
    out["spindle"] = {{"set_hz", rounded(view->spindle_set_hz, 0.1)},
                      {"actual_hz", rounded(view->spindle_hz, 0.1)}};
  }
  return out;
}

}  // namespace cellctl::web

#include "web/cell_board.hpp"

#include <cmath>

namespace cellctl::web {
namespace {

// Positions to the µm the SCU and the encoder resolve at best; times to the ms.
double rounded(double v, double resolution) {
  return std::round(v / resolution) * resolution;
}

std::optional<double> position(bool known, double mm) {
  return known ? std::optional<double>(rounded(mm, 0.001)) : std::nullopt;
}

const char* link_word(const status::StatusView& v, std::size_t d) {
  if (v.link_fault[d]) return "lost";
  return v.link_active[d] ? "up" : "down";
}

}  // namespace

schema::Board board_view(const std::vector<std::string>& axis_names,
                         const std::optional<status::StatusView>& view, bool live) {
  schema::Board b;
  for (std::size_t i = 0; i < axis_names.size(); ++i) {
    schema::BoardAxis a{axis_names[i], std::nullopt};
    if (view && i < view->axes && i < cell::kMaxAxes) {
      const auto& v = *view;
      a.read = schema::BoardAxis::Read{
          position(v.target_known[i], v.target_mm[i]), position(v.position_known[i], v.scu_mm[i]),
          position(v.encoder_measures[i], v.encoder_mm[i]), v.home_recorded[i], v.scu_initialised[i]};
    }
    b.axes.push_back(std::move(a));
  }
  b.live = view && live;
  if (!view) return b;
  const auto& v = *view;
  for (std::size_t d = 0; d < v.devices.size(); ++d) {
    if (v.devices[d].empty()) continue;  // a slot without a device
    const auto& c = v.link_counts[d];
    // The run's own verdict once its stop has resolved the device (cellctl run has no run records).
    b.devices.push_back({std::string(v.devices[d]), link_word(v, d),
                         rounded(v.link_round_trip_s[d] * 1e3, 0.1), rounded(v.link_silent_s[d], 0.001),
                         c.good_replies, c.timeouts, c.bad_frames, c.refusals,
                         v.safe[d].empty() ? std::nullopt : std::optional<std::string>(v.safe[d])});
  }
  b.t = rounded(v.t, 0.001);
  b.spindle = schema::Board::Spindle{rounded(v.spindle_set_hz, 0.1), rounded(v.spindle_hz, 0.1)};
  return b;
}

}  // namespace cellctl::web

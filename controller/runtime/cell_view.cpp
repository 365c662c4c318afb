#include "runtime/cell_view.hpp"

namespace cellctl::runtime {

void show_cell(const cell::CellState& s, const routines::HomeRecord& home, const CellDevices& devices,
               status::StatusView& v) noexcept {
  v.axes = s.axis_count;
  for (std::size_t i = 0; i < s.axis_count; ++i) {
    const auto& axis = s.axes[i];
    v.position_mm[i] = axis.position_mm();
    v.position_known[i] = axis.present;
    v.scu_mm[i] = axis.scu_mm;
    v.encoder_measures[i] = axis.measured;
    v.encoder_mm[i] = axis.encoder_mm;
    v.home_recorded[i] = home.axes[i].homed;
    v.scu_initialised[i] = axis.scu_initialised;
  }
  v.spindle_hz = s.spindle.actual_hz;
  for (std::size_t d = 0; d < cell::kMaxDevices; ++d) {
    v.devices[d] = s.devices[d];
    v.link_active[d] = s.links[d].active;
    v.link_fault[d] = s.links[d].fault;
    v.link_silent_s[d] = link::to_seconds(s.links[d].silent_for);
    v.link_counts[d] = s.links[d].counts;
  }
  for (const auto* d : devices.devices())
    v.link_round_trip_s[d->slot()] = link::to_seconds(d->session().health().last_round_trip);
}

}  // namespace cellctl::runtime

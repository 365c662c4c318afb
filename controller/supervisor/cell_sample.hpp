#pragma once
// The journal's sample of the cell as it stands: each axis's SCU position, the encoder's position and
// speed where it measures an axis, the spindle's speed — with each axis planned where it stands and
// no spindle speed asked for, as at rest. A run's supervisor puts its own plan and set speed over
// those; `cellctl serve`'s look at the cell before any job tells it as it is (the plant's Idle
// status). Allocates nothing: the cycle calls it.

#include "cell/cell_state.hpp"
#include "journal/event.hpp"

namespace cellctl::supervisor {

[[nodiscard]] inline journal::Sample cell_sample(const cell::CellState& s) noexcept {
  journal::Sample smp;
  smp.axes = s.axis_count;
  for (std::size_t i = 0; i < s.axis_count && i < journal::kMaxAxes; ++i) {
    smp.planned_mm[i] = static_cast<float>(s.axes[i].position_mm());
    smp.scu_mm[i] = static_cast<float>(s.axes[i].scu_mm);
    if (s.axes[i].measured) {
      smp.encoder_mm = static_cast<float>(s.axes[i].encoder_mm);
      smp.encoder_mm_s = static_cast<float>(s.axes[i].encoder_mm_s);
    }
  }
  smp.spindle_actual_hz = static_cast<float>(s.spindle.actual_hz);
  return smp;
}

}  // namespace cellctl::supervisor

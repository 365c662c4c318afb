#pragma once
// The resolution each number of the plant's status is published to: what the device that measures it
// can tell apart, never a float's binary expansion (20.600000381469727). Chosen from the devices:
//   - an axis's positions, planned and SCU-reported: the SCU's edge (1 / edges_per_mm of the axis) as
//     the decimals that resolve it: 10 edges/mm (the default cell) → 0.1 mm, 100 → 0.01 mm, 3 → 0.1 mm;
//   - the encoder: 0.0001 mm, finer than a count (the default cell's SCH88BEX: 4 mm per turn of 8192
//     steps, 0.49 µm) and the journal's own resolution (schema/journal_line.hpp);
//   - the spindle: whole Hz, as the e@syDrive's set and actual frequency (P10, P13) travel on the wire;
//   - the loop's jitter 0.1 µs, the progress 0.001.

#include "config/cell_core.hpp"

namespace cellctl::plant_link {

inline constexpr int kEncoderDecimals = 4;
inline constexpr int kSpindleDecimals = 0;
inline constexpr int kJitterDecimals = 1;
inline constexpr int kProgressDecimals = 3;

// The decimals that resolve one edge of the axis's SCU (3 when the axis has no scaling).
[[nodiscard]] int position_decimals(const config::AxisConfig& axis) noexcept;

// v to `decimals` places, as a double that prints as such (20.6, never -0).
[[nodiscard]] double to_decimals(double v, int decimals) noexcept;

}  // namespace cellctl::plant_link

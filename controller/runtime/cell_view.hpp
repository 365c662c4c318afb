#pragma once
// What the status board shows of the cell itself, whoever reads it — a job's run every cycle, or
// `cellctl serve`'s look at the cell before its first job (cell_look.hpp): per axis the SCU's and the
// encoder's positions and the two facts that make it homed, the spindle's speed, and per device slot
// its name and its link. A run adds what is its own (state, step, targets, the loop's jitter,
// faults). Allocates nothing: the cycle calls it.

#include "cell/cell_state.hpp"
#include "routines/home_record.hpp"
#include "runtime/cell_devices.hpp"
#include "status/status_view.hpp"

namespace cellctl::runtime {

void show_cell(const cell::CellState& s, const routines::HomeRecord& home, const CellDevices& devices,
               status::StatusView& v) noexcept;

}  // namespace cellctl::runtime

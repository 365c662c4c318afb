#pragma once
// One link per device slot of the cell, from one side of the lines: the sessions' ends (master side) or
// the emulators' ends (device side). nullptr: the cell has no device in that slot, or it is not emulated.

#include <array>

#include "cell/cell_state.hpp"
#include "link/link.hpp"

namespace cellctl::runtime {

using DeviceLinks = std::array<link::Link*, cell::kMaxDevices>;

}  // namespace cellctl::runtime

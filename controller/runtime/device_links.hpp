#pragma once
// One link per device of the cell, from one side of the lines: the sessions' ends (master side) or
// the emulators' ends (device side). nullptr: the cell has no such device, or it is not emulated.

#include "link/link.hpp"

namespace cellctl::runtime {

struct DeviceLinks {
  link::Link* scu = nullptr;
  link::Link* spindle = nullptr;
  link::Link* encoder = nullptr;
};

}  // namespace cellctl::runtime

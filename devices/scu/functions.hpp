#pragma once
// Which actuators each motion function F1..F10 moves: the SCU's parameterization, which the cell config
// must state because the protocol cannot tell. The standard "SCP11" maps Fn to actuator n; other units
// have functions that move several actuators, optionally with position synchronisation.

#include <array>
#include <bitset>

#include "scu/protocol.hpp"

namespace cellctl::scu {

struct FunctionDef {
  bool defined = false;
  std::bitset<kActuatorCount> actuators;  // bit a-1 = actuator a
  bool synchronized = false;              // synchronized parallel run (bit 21 guards it)
  [[nodiscard]] bool moves(int actuator) const noexcept {
    return defined && actuators.test(static_cast<std::size_t>(actuator - 1));
  }
};

// functions[f-1] is Ff.
using FunctionTable = std::array<FunctionDef, kMotionFunctionCount>;

// SCP11 for the given actuators: Fa moves actuator a alone.
[[nodiscard]] inline FunctionTable scp11(std::bitset<kActuatorCount> present) noexcept {
  FunctionTable t{};
  for (std::size_t a = 0; a < kActuatorCount; ++a) {
    if (!present.test(a)) continue;
    t[a].defined = true;
    t[a].actuators.set(a);
  }
  return t;
}

}  // namespace cellctl::scu

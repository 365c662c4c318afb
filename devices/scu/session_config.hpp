#pragma once
// How the master drives one SCU: remote-mode safety, keep-alive and reply timing, retries, when
// silence becomes a link fault, which actuators and functions the cell has, and each actuator's
// scaling (edges per mm) and full speed — the session converts to and from mm and mm/s with them.

#include <array>
#include <bitset>
#include <chrono>
#include <cstdint>

#include "link/clock.hpp"
#include "scu/functions.hpp"

namespace cellctl::scu {

// What the program must know of a fitted actuator; the SCU's own parameterization says the same.
struct ActuatorSpec {
  double edges_per_mm = 100.0;    // SCU positions are encoder edges
  double stroke_mm = 200.0;       // its travel from fully in
  double full_speed_mm_s = 20.0;  // what 100 % remote speed is
};

struct SessionConfig {
  std::uint8_t safety_id = 0;  // RO parameter: 0, 1 or 2 (manual 4.1)
  // RC period; must stay well inside the SCU's 500 ms watchdog. Zero = back to back, as fast as the
  // line allows (RC whenever nothing else is queued).
  link::Duration keepalive_period = std::chrono::milliseconds(100);
  link::Duration reply_timeout = std::chrono::milliseconds(150);
  int retries = 2;  // further attempts after a time-out or a CSE
  link::Duration link_fault_after = std::chrono::milliseconds(1000);
  // How long the fitted actuators take at most to stand still once the SCU terminates their motion
  // (a communication time-out, RA, F20), from full speed. With the SCU's communication time-out
  // (0.5 s after the last RC or RO it received, whatever the Safety_ID: every motion of ours is a
  // remote one) it bounds when axes the program lost sight of are surely at rest.
  link::Duration stopping_time = std::chrono::milliseconds(500);
  std::bitset<kActuatorCount> actuators = 1;  // bit a-1 = actuator a is fitted
  FunctionTable functions = scp11(1);
  std::array<ActuatorSpec, kActuatorCount> specs{};  // specs[a-1]: actuator a, when fitted
  // A move has "arrived" when every actuator ended within this of its target.
  std::int32_t arrival_tolerance_edges = 5;
};

// Throws std::invalid_argument naming the field and the value.
void validate(const SessionConfig& c);

}  // namespace cellctl::scu

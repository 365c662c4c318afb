#pragma once
// What the supervisor wants of the devices, as a level (the desired state), rebuilt every cycle.
// CellDevices turns changes of it into session commands; a new move is asked for by bumping
// move_id, so the same intent held over many cycles sends one command.

#include <array>
#include <cstdint>

#include "cell/cell_state.hpp"

namespace cellctl::cell {

struct AxisIntent {
  std::uint32_t move_id = 0;  // changes when a new move starts
  bool move = false;          // a move to target_mm is wanted (false: the axis should be still)
  double target_mm = 0.0;     // in the SCU's frame (corrections included)
  double speed_mm_s = 0.0;    // may change during the move (speed modulation)
  bool soft = true;           // ramps on start and stop
  // Where the profile says the axis should be now, and how fast: the monitor's following-error rule
  // holds the measured position to it while `move` is set.
  double planned_mm = 0.0;
  double planned_mm_s = 0.0;
};

struct SpindleIntent {
  bool run = false;
  double frequency_hz = 0.0;
  bool clockwise = true;
  bool reset = false;  // clear a converter fault (operator reset)
};

// A preset of the encoder's position (its preset handshake), asked for once per new preset_id.
struct EncoderIntent {
  std::uint32_t preset_id = 0;  // 0: none asked
  double preset_mm = 0.0;
};

enum class Halt : std::uint8_t {
  none,
  controlled,  // stop categories 1 and 2: soft stop of every axis, spindle down on its ramp
  immediate,   // stop category 0: SCU emergency stop (F20) and spindle stop at once
};

struct Intents {
  std::array<AxisIntent, kMaxAxes> axes{};
  SpindleIntent spindle;
  EncoderIntent encoder;
  Halt halt = Halt::none;
};

}  // namespace cellctl::cell

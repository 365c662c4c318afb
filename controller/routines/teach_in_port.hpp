#pragma once
// What the Teach-In routine may ask of the encoder beyond the cycle's CellState, in the program's
// units: switch its parameters (the manual's prerequisites for Teach-In, the configured ones back, the
// taught ones), start and end Teach-In, and read where it stands. Implemented at the device boundary
// (runtime/teach_in_encoder), so the routine sees no device header.

#include <cstdint>
#include <string_view>

#include "link/clock.hpp"

namespace cellctl::routines {

enum class EncoderSetting : std::uint8_t {
  configured,  // the cell config's parameters
  teach_in,    // the manual's prerequisites for Teach-In (4.4.2.1)
  taught,      // the configured ones with the total resolution of the last Teach-In
};

enum class EncoderCommand : std::uint8_t { idle, busy, done, failed };

struct EncoderView {
  bool up = false;  // in data exchange with the setting last asked for, Ready set
  bool teach_in_running = false;
  double position_mm = 0.0;        // as a run reads it (during Teach-In: from the native zero, unscaled)
  double native_range_mm = 0.0;    // the encoder's physical measuring range
  std::int32_t stored_offset = 0;  // its preset offset (diagnosis 4.2.14); 0 when not reported
  EncoderCommand command = EncoderCommand::idle;
  std::string_view failure;            // of a failed command or switch (static text)
  std::uint32_t total_resolution = 0;  // after Teach-In ended
};

class TeachInPort {
 public:
  virtual ~TeachInPort() = default;
  // Why this encoder cannot do Teach-In with the configured parameters, or empty.
  [[nodiscard]] virtual std::string_view unavailable() const = 0;
  // Starts re-parameterising; read().up once the encoder exchanges data with the new setting.
  virtual void switch_to(EncoderSetting setting, link::TimePoint now) = 0;
  [[nodiscard]] virtual bool start_teach_in() = 0;
  // Ends Teach-In telling the encoder the distance travelled (in the taught unit: mm × units per mm).
  [[nodiscard]] virtual bool end_teach_in(double distance_mm) = 0;
  virtual void clear_command() = 0;
  [[nodiscard]] virtual EncoderView read() const = 0;
};

}  // namespace cellctl::routines

#pragma once
// The SCH88BEX's own behaviour, without the bus: physical position → measuring units (code sequence,
// scaling, preset offset), status bits, limit switches, velocity and acceleration sampled over the
// time base, the slave's side of the preset / direction / Teach-In handshakes (manual 4.3, 4.4, the
// tables read row by row), alarms and warnings, and the extended diagnosis. Pure: time comes in as
// arguments; what must survive a power cycle is in NonVolatile, which the emulator stores.

#include <cstdint>
#include <optional>

#include "encoder/cyclic.hpp"
#include "encoder/diagnosis.hpp"
#include "encoder/parameters.hpp"
#include "encoder/scaling.hpp"
#include "link/clock.hpp"

namespace cellctl::encoder {

// The encoder's EEPROM: the preset offset (4.2.14), the counting direction set on the fly (4.4.1),
// the Total resolution of the last Teach-In (4.4.2) and the address set over the bus (3.4).
struct NonVolatile {
  std::int32_t offset = 0;
  CodeSequence code_sequence = CodeSequence::cw;
  std::uint32_t taught_units = 0;  // 0: no Teach-In
  std::uint8_t address = 0;        // 0: none stored (the rotary switches decide)
  friend bool operator==(const NonVolatile&, const NonVolatile&) = default;
};

struct DeviceIdentity {
  PhysicalResolution physical;
  Version profile_version{1, 1};
  Version software_version{2, 0};
  std::array<char, 10> serial{'*', '*', '*', '*', '*', '*', '*', '*', '*', '*'};  // 4.2.18
};

class EncoderDevice {
 public:
  EncoderDevice(const DeviceIdentity& identity, const NonVolatile& eeprom) noexcept;

  // Accepted parameters (already checked by decode_user_prm/validate). Re-parameterisation sets
  // the code sequence and the scaling from the parameters (4.4.2: a taught value is overwritten).
  void parameterize(const EncoderParameters& p) noexcept;
  [[nodiscard]] const EncoderParameters& parameters() const noexcept { return params_; }

  // The shaft stands at `revolutions` (clockwise positive) at `now`; velocity/acceleration are
  // sampled once per time-base period.
  void sample(double revolutions, link::TimePoint now) noexcept;
  // One Data_Exchange: act on the output word's edges (nullopt for Class 1) and give the input.
  [[nodiscard]] CyclicInput exchange(std::optional<std::uint32_t> output) noexcept;
  // Outputs to the safe state (watchdog, Clear_Data): a held handshake bit counts as released.
  void release_outputs() noexcept { last_output_ = 0; }

  // Fault injection: alarm:: and warning:: bits (only the supported ones are accepted).
  void set_alarm(std::uint16_t mask, bool on) noexcept;
  void set_warning(std::uint16_t mask, bool on) noexcept;
  void add_operating_time(link::Duration d) noexcept;
  [[nodiscard]] std::uint8_t alarms() const noexcept { return alarms_; }
  [[nodiscard]] std::uint16_t warnings() const noexcept { return warnings_; }

  [[nodiscard]] EncoderDiagnosis diagnosis() const noexcept;
  [[nodiscard]] const NonVolatile& eeprom() const noexcept { return eeprom_; }
  void set_stored_address(std::uint8_t address) noexcept { eeprom_.address = address; }
  [[nodiscard]] bool teach_in_running() const noexcept { return teach_in_; }
  // The position in measuring units now (what the next input will carry without a handshake).
  [[nodiscard]] std::uint32_t position() const noexcept;

 private:
  [[nodiscard]] std::uint64_t coded_physical() const noexcept;  // 0 … total − 1, after code sequence
  [[nodiscard]] std::uint32_t status_word() const noexcept;
  void on_edges(std::uint32_t out) noexcept;
  void finish_teach_in() noexcept;

  DeviceIdentity identity_;
  NonVolatile eeprom_;
  EncoderParameters params_;
  Scaling scaling_;
  std::uint64_t total_;

  double revolutions_ = 0.0;
  std::optional<link::TimePoint> sampled_at_;
  double sampled_units_ = 0.0;  // unwrapped, in the velocity's units, at sampled_at_
  double velocity_ = 0.0;       // per time base
  std::int16_t velocity16_ = 0;
  std::int16_t acceleration16_ = 0;

  std::uint32_t last_output_ = 0;
  bool preset_ack_ = false;
  bool direction_ack_ = false;
  bool teach_in_ = false;
  std::uint64_t teach_start_ = 0;
  std::optional<std::uint32_t> teach_result_;  // set while bit 29 is acknowledged
  std::uint8_t alarms_ = 0;
  std::uint16_t warnings_ = 0;
  std::uint64_t operating_time_ns_ = 0;
};

}  // namespace cellctl::encoder

#pragma once
// The encoder's DP master: a profibus::DpMaster set up with this encoder's Prm/Cfg (from typed
// EncoderParameters), a typed snapshot per cycle (position in counts and mm, velocity in mm/s,
// status bits, decoded diagnosis, start-up faults with the rule broken) and the manufacturer
// functions as handshakes that run across cycles. Driven through link::DeviceSession: receive(now)
// steps the DP master (which exchanges data on its own cyclic schedule) and publishes the snapshot;
// transmit(now) hands this cycle's output word to the master for its next Data_Exchange. Neither
// waits nor allocates (a fault reason is formatted into capacity reserved at construction).

#include <cstdint>
#include <optional>
#include <string>

#include "encoder/cyclic.hpp"
#include "encoder/diagnosis.hpp"
#include "encoder/handshake.hpp"
#include "encoder/parameters.hpp"
#include "encoder/scaling.hpp"
#include "link/device_session.hpp"
#include "link/link.hpp"
#include "profibus/dp_master.hpp"

namespace cellctl::encoder {

struct SessionConfig {
  std::uint8_t station_address = 1;  // 126: only set_slave_address() is possible
  EncoderParameters parameters;
  PhysicalResolution physical;   // of the encoder in use: for the local parameter check
  profibus::DpMasterConfig bus;  // master address, line, slot time, retries, watchdog, lost time
  // Length per count: exactly one of the two is > 0 (mm_per_revolution uses the units per revolution).
  double counts_per_mm = 0.0;
  double mm_per_revolution = 0.0;
  // The encoder's reading in mm where the axis is at 0 mm: position_mm = reading − zero_offset_mm.
  double zero_offset_mm = 0.0;
  // The preset offset (diagnosis octets 32–35, manual 4.2.14) the encoder must hold: a stored offset
  // that differs (a preset since the config was written) faults the session at start-up with both
  // values. nullopt: not checked (the commissioning commands, which change it).
  std::optional<std::int32_t> expected_offset;
};

// Where a command (handshake) stands.
struct CommandStatus {
  Handshake::Kind kind = Handshake::Kind::none;
  Handshake::Phase phase = Handshake::Phase::idle;
  std::uint32_t result = 0;  // preset/direction: position; Teach-In end: total resolution
  std::string_view failure;  // static text when failed
};

struct Snapshot {
  profibus::DpState dp_state = profibus::DpState::stopped;
  bool data_exchange = false;
  std::uint64_t exchanges = 0;   // Data_Exchange replies of the configured length so far
  link::Duration input_age{};    // since the last valid input (none yet: since the activation)
  bool had_valid_input = false;  // a valid input since the activation: input_age counts from it
  // The position, velocity and acceleration below are from the last input; they are the encoder's
  // measurement only while input_valid. An input the manual does not allow (bit 31 set without
  // status bits), or one the encoder flags (Ready clear, Teach-In running: unscaled, a direction
  // acknowledge in the position bits), makes them invalid and counts in bad_inputs.
  bool input_valid = false;
  std::string_view input_fault;  // why the last input is not valid (static text); empty when valid
  std::uint64_t bad_inputs = 0;  // inputs not taken: wrong length (master) or invalid here

  std::uint32_t position_counts = 0;  // measuring units (during Teach-In: physical steps, offset 0)
  // The counts read as signed around the encoder's output zero (a reading in the upper half of the
  // range is below zero, not ≈ the whole range above it), in mm, less zero_offset_mm.
  double position_mm = 0.0;
  std::int16_t velocity_raw = 0;  // in the time base's unit
  bool velocity_saturated = false;
  double velocity_mm_s = 0.0;
  std::int16_t acceleration_raw = 0;
  bool acceleration_saturated = false;
  double acceleration_mm_s2 = 0.0;
  bool has_status_bits = false;
  StatusBits status;  // meaningful when has_status_bits

  profibus::StandardDiag standard_diag;
  std::optional<EncoderDiagnosis> diagnosis;  // the last extended diagnosis that decoded
  std::uint64_t diagnosis_reads = 0;
  // Of the last diagnosis read: its extended octets (0: none, only the standard part) and why they
  // did not decode as the encoder profile's (empty when they did or there were none).
  std::size_t extended_diag_octets = 0;
  std::string_view diagnosis_error;
  // The encoder raised new diagnosis (DH) during data exchange since the previous receive(): a pulse.
  bool new_diagnosis = false;

  std::optional<PrmViolation> local_prm_violation;  // refused here before anything was sent
  profibus::StartupFault::Kind startup_fault = profibus::StartupFault::Kind::none;  // what the slave said
  CommandStatus command;
};

class Session final : public link::DeviceSession {
 public:
  // Throws std::invalid_argument naming the field and value (scale factors, bus settings).
  Session(link::Link& link, const SessionConfig& config);

  void activate(link::TimePoint now) override;
  void deactivate(link::TimePoint now) override;
  void receive(link::TimePoint now) override;
  void transmit(link::TimePoint now) override;
  [[nodiscard]] const link::LinkHealth& health() const noexcept override { return master_.health(); }
  [[nodiscard]] bool awaiting_reply() const noexcept override { return false; }
  [[nodiscard]] std::optional<link::TimePoint> next_deadline() const noexcept {
    return master_.next_deadline();
  }

  [[nodiscard]] const Snapshot& snapshot() const noexcept { return snapshot_; }
  // Why the DP start-up was last begun again (slave lost, left data exchange …); empty before.
  [[nodiscard]] const std::string& restart_reason() const noexcept { return master_.restart_reason(); }
  [[nodiscard]] const SessionConfig& config() const noexcept { return config_; }
  [[nodiscard]] double counts_per_mm() const noexcept { return counts_per_mm_; }
  [[nodiscard]] const Scaling& scaling() const noexcept { return scaling_; }
  // Physical steps per mm of the axis (what Teach-In counts in: unscaled, manual 4.4.2.1).
  [[nodiscard]] double steps_per_mm() const noexcept;
  // New parameters and scaling for the next activation (Set_Prm and Chk_Cfg are sent again then):
  // only while inactive (false otherwise). Throws std::invalid_argument as the constructor does.
  [[nodiscard]] bool reconfigure(const SessionConfig& config);

  // Commands: false when not in data exchange, another command runs, or the function is not
  // available with these parameters (value beyond the range; direction/Teach-In need the status
  // bits and commissioning mode). Progress in snapshot().command; clear_command() after done/failed.
  [[nodiscard]] bool preset(std::uint32_t value) noexcept;
  [[nodiscard]] bool set_direction(CodeSequence wanted) noexcept;
  [[nodiscard]] bool teach_in_start() noexcept;
  [[nodiscard]] bool teach_in_end(std::uint32_t distance) noexcept;
  void clear_command() noexcept;
  // Set_Slave_Add for an encoder at station 126 (rotary switches at 0x7E, manual 3.4).
  [[nodiscard]] bool set_slave_address(std::uint8_t new_address) noexcept;
  [[nodiscard]] profibus::RequestStatus address_change_status() const noexcept {
    return master_.address_change_status();
  }

 private:
  [[nodiscard]] bool manufacturer_function_allowed() const noexcept;
  void on_input(std::span<const std::uint8_t> bytes) noexcept;
  [[nodiscard]] std::string_view flagged(const CyclicInput& in) const noexcept;
  void push_outputs() noexcept;
  void update_lifecycle();
  void check_offset() noexcept;

  SessionConfig config_;
  Scaling scaling_;
  double counts_per_mm_;
  profibus::DpMaster master_;
  Handshake handshake_;
  std::uint64_t seen_exchanges_ = 0;
  std::uint64_t seen_diag_reads_ = 0;
  std::uint64_t outputs_changed_at_ = 0;  // exchange count when the output word last changed
  std::uint32_t output_word_ = 0;
  Snapshot snapshot_;
  bool offset_refused_ = false;  // the stored preset offset is not the configured one (a fault)
};

}  // namespace cellctl::encoder

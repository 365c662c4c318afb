#pragma once
// The emulated SCH88BEX: a profibus::DpSlave whose behaviour is this encoder — parameters judged by
// the manual's rules (Prm_Fault), the extended diagnosis, the shaft of a plant::Shaft turned into
// counts, and the handshakes of EncoderDevice. Its EEPROM lives in a state file. Stepped by
// poll(now) over any Link.
//
// The functionality is the master's choice, as on the real encoder (manual 4: "selected in the
// Master Set-up Tool"), never a setting of the emulator. DP sends Set_Prm before Chk_Cfg, and the
// three Scancon functionalities share one 32-octet User_Prm_Data, so the choice is made in two steps
// (our reading: devices/encoder/README.md):
//   Set_Prm  the User_Prm_Data length names the family — 2 octets Class 1, 18 Class 2, 32 Scancon —
//            and the parameters are judged by the manual's rules for it (else Prm_Fault);
//   Chk_Cfg  the configuration identifiers name the functionality (one GSD module each); it must be
//            of the family the parameters were for, and the parameters must be allowed for it
//            (Without Status Bits only with Scancon 3.0) — else Cfg_Fault, with the reason kept.
// Only then is the encoder parameterised and data exchange begins with that functionality's data.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "encoder/encoder_device.hpp"
#include "link/link.hpp"
#include "plant/shaft.hpp"
#include "profibus/dp_slave.hpp"
#include "profibus/slave_behaviour.hpp"
#include "wire/fixed_bytes.hpp"

namespace cellctl::encoder {

struct EmulatorConfig {
  std::uint8_t address = 1;  // the rotary switches: 1..125, or 126 (address set over the bus)
  DeviceIdentity identity;
  link::LineFormat line = link::line_8e1(1'500'000);
  std::filesystem::path state_file;  // empty: EEPROM not kept across restarts
};

class Emulator {
 public:
  // Throws std::invalid_argument (address, physical resolution) or std::runtime_error (state file).
  Emulator(link::Link& link, const EmulatorConfig& config, const plant::Shaft& shaft);

  void poll(link::TimePoint now);
  [[nodiscard]] std::optional<link::TimePoint> next_deadline() const noexcept {
    return slave_.next_deadline();
  }

  // Fault injection: alarm::position_error / supply_voltage; warning::temperature_exceeded /
  // light_control_reserve / operating_time_limit / battery_charge. A change raises a diagnosis (DH).
  void set_alarm(std::uint16_t mask, bool on) noexcept;
  void set_warning(std::uint16_t mask, bool on) noexcept;
  // A slave that stops answering (and starts again).
  void set_silent(bool silent) noexcept { slave_.set_silent(silent); }
  // A slave whose every input octet is 0xff (`ff ff ff ff` for Class 2: bit 31 set, which the manual
  // says is always 0): what a broken or third-party slave may send. The master must not take it for
  // a position (its session marks it invalid).
  void set_inputs_all_ones(bool on) noexcept { behaviour_.inputs_all_ones = on; }

  [[nodiscard]] const profibus::DpSlave& slave() const noexcept { return slave_; }
  [[nodiscard]] const EncoderDevice& device() const noexcept { return behaviour_.device; }
  // Why the last Set_Prm was refused (the rule), empty when accepted.
  [[nodiscard]] std::string_view last_prm_reason() const noexcept { return slave_.last_prm_reason(); }
  // Why the last Chk_Cfg was refused, empty when accepted.
  [[nodiscard]] std::string_view last_cfg_reason() const noexcept { return behaviour_.cfg_reason; }
  [[nodiscard]] std::uint64_t watchdog_expiries() const noexcept {
    return slave_.counters().watchdog_expiries;
  }

 private:
  struct Behaviour final : profibus::SlaveBehaviour {
    Behaviour(const EmulatorConfig& c, const NonVolatile& nv) : config(c), device(c.identity, nv) {}
    [[nodiscard]] Functionality functionality() const noexcept { return device.parameters().functionality; }
    profibus::PrmVerdict check_prm(std::span<const std::uint8_t> user_prm) override;
    bool check_cfg(std::span<const std::uint8_t> cfg) override;
    std::size_t ext_diag(std::span<std::uint8_t> out) override;
    std::size_t exchange(std::span<const std::uint8_t> outputs, std::span<std::uint8_t> inputs) override;
    bool diag_pending() override { return diag_changed; }
    void on_watchdog_expired() override { device.release_outputs(); }
    void on_clear_data() override { device.release_outputs(); }
    void on_address_changed(std::uint8_t new_address, bool no_add_chg) override;

    const EmulatorConfig& config;
    EncoderDevice device;
    std::string prm_reason;  // kept here: DpSlave holds a view of it
    std::string cfg_reason;
    // The User_Prm_Data of the accepted Set_Prm, judged for its family, until Chk_Cfg names the
    // functionality.
    wire::FixedBytes<64> accepted_prm;
    std::optional<Functionality> accepted_family;
    bool diag_changed = false;
    bool inputs_all_ones = false;  // set_inputs_all_ones
  };

  [[nodiscard]] static std::uint8_t start_address(const EmulatorConfig& c, const NonVolatile& nv);

  EmulatorConfig config_;
  const plant::Shaft& shaft_;
  NonVolatile saved_;
  Behaviour behaviour_;
  profibus::DpSlave slave_;
  std::optional<link::TimePoint> last_poll_;
};

}  // namespace cellctl::encoder

#pragma once
// The e@syDrive's RS232 messages as typed values (manual chapter 5). Raw fields keep the converter's
// integer units (A/100, V/100, W/10); the accessors give SI values, so nothing above the codec scales.

#include <cstdint>
#include <variant>

namespace cellctl::spindle {

// The MSGID byte of every message the manual defines.
enum class MsgId : std::uint8_t {
  set_basic = 0x10,      // SET Grundparameter: P1 set-point, P8 display unit
  set_start = 0x18,      // SET Startparameter: P140, P141, P146
  res_status = 0x59,     // RES Anzeigewerte (Status)
  res_ident = 0x5A,      // RES Anzeigewerte (Kennung)
  res_statusout = 0x60,  // RES Statusout
  cmd_start = 0xA0,
  cmd_stop = 0xA1,
  cmd_reset = 0xA2,
  request = 0xCF,  // REQ: asks for one of the three RES messages
  ack = 0xFF,      // ACK: data is the MSGID acknowledged
};

// P8: how the converter's own software shows speed. No effect on the wire values (always Hz).
enum class SpeedUnit : std::uint8_t { hz = 0x01, rpm = 0x02 };
// P140 start source / P141 set-point source. Only `sycodrive` (RS232) lets this program start the motor.
enum class Source : std::uint8_t {
  sycodrive = 0x01,
  digital_input = 0x02,
  can = 0x03,
  analog_voltage = 0x04,
  analog_current = 0x05
};
// P146. Rechtslauf = clockwise, Linkslauf = counter-clockwise.
enum class Direction : std::uint8_t { clockwise = 0x01, counter_clockwise = 0x02, digital_input = 0x03 };
// statusout2.
enum class DeviceState : std::uint8_t { none = 0x00, warning = 0x02, fault = 0x03 };

struct SetBasic {
  std::uint16_t frequency_hz = 0;  // P1
  SpeedUnit unit = SpeedUnit::hz;  // P8
  friend bool operator==(const SetBasic&, const SetBasic&) = default;
};

struct SetStart {
  Source start_source = Source::sycodrive;     // P140
  Source setpoint_source = Source::sycodrive;  // P141
  Direction direction = Direction::clockwise;  // P146
  friend bool operator==(const SetStart&, const SetStart&) = default;
};

// CMD System Start / Stopp / Reset: no data, told apart by MSGID.
struct Command {
  MsgId id = MsgId::cmd_stop;  // cmd_start, cmd_stop or cmd_reset
  friend bool operator==(const Command&, const Command&) = default;
};

struct Request {
  MsgId wanted = MsgId::res_statusout;  // res_status, res_ident or res_statusout
  friend bool operator==(const Request&, const Request&) = default;
};

struct Ack {
  MsgId acknowledged = MsgId::cmd_stop;  // the SET or CMD this confirms
  friend bool operator==(const Ack&, const Ack&) = default;
};

// RES 0x59, 27 data bytes.
struct StatusValues {
  std::uint16_t set_frequency_hz = 0;     // P10
  std::uint16_t peak_current_ca = 0;      // P11, A/100: the current limit in force
  std::uint16_t actual_frequency_hz = 0;  // P13
  std::uint16_t motor_voltage_cv = 0;     // P15, V/100
  std::uint16_t dc_link_voltage_cv = 0;   // P16, V/100
  std::uint16_t motor_current_ca = 0;     // P18, A/100
  std::uint16_t power_dw = 0;             // P19, W/10
  std::uint8_t motor_code = 0;            // P20
  std::uint32_t converter_hours = 0;      // P25
  std::uint32_t motor_hours = 0;          // P26

  [[nodiscard]] double peak_current_a() const noexcept { return peak_current_ca / 100.0; }
  [[nodiscard]] double motor_voltage_v() const noexcept { return motor_voltage_cv / 100.0; }
  [[nodiscard]] double dc_link_voltage_v() const noexcept { return dc_link_voltage_cv / 100.0; }
  [[nodiscard]] double motor_current_a() const noexcept { return motor_current_ca / 100.0; }
  [[nodiscard]] double power_w() const noexcept { return power_dw / 10.0; }
  friend bool operator==(const StatusValues&, const StatusValues&) = default;
};

// RES 0x5A, 13 data bytes.
struct Identification {
  std::uint8_t fault_history[5] = {};  // P30 (latest) … P34 (fifth latest); 0 = none
  std::uint16_t converter_type = 0;    // P36
  std::uint16_t firmware = 0;          // P37
  std::uint32_t serial_number = 0;     // P39
  friend bool operator==(const Identification&, const Identification&) = default;
};

// RES 0x60, 4 data bytes.
struct StatusOut {
  std::uint8_t error_number = 0;          // statusout1: the warning's or fault's number
  DeviceState state = DeviceState::none;  // statusout2
  std::uint8_t flags = 0;                 // statusout3, see the k…Flag masks
  std::uint8_t motor_code = 0;            // statusout4: 0 inactive, 1..16 = M1..M16

  static constexpr std::uint8_t kAtRestFlags = 0x03;          // bits 0 and 1 both say STILLSTAND
  static constexpr std::uint8_t kAtSpeedFlag = 0x04;          // N_Soll_OK
  static constexpr std::uint8_t kCurrentLimitFlag = 0x08;     // WARNSTROM
  static constexpr std::uint8_t kOverTemperatureFlag = 0x10;  // MOTORTEMPERATUR (PTC)

  [[nodiscard]] bool at_rest() const noexcept { return (flags & kAtRestFlags) != 0; }
  [[nodiscard]] bool at_speed() const noexcept { return (flags & kAtSpeedFlag) != 0; }
  [[nodiscard]] bool current_limit() const noexcept { return (flags & kCurrentLimitFlag) != 0; }
  [[nodiscard]] bool over_temperature() const noexcept { return (flags & kOverTemperatureFlag) != 0; }
  friend bool operator==(const StatusOut&, const StatusOut&) = default;
};

using Message =
    std::variant<SetBasic, SetStart, Command, Request, Ack, StatusValues, Identification, StatusOut>;

// The data length (LEN) each MSGID must carry, or -1 for an ID the manual does not define.
[[nodiscard]] constexpr int data_length(std::uint8_t id) noexcept {
  switch (static_cast<MsgId>(id)) {
    case MsgId::set_basic:
      return 4;
    case MsgId::set_start:
      return 3;
    case MsgId::res_status:
      return 27;
    case MsgId::res_ident:
      return 13;
    case MsgId::res_statusout:
      return 4;
    case MsgId::cmd_start:
    case MsgId::cmd_stop:
    case MsgId::cmd_reset:
      return 0;
    case MsgId::request:
    case MsgId::ack:
      return 1;
  }
  return -1;
}

// The MSGID a message goes out with.
[[nodiscard]] MsgId id_of(const Message& m) noexcept;

}  // namespace cellctl::spindle

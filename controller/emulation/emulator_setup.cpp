#include "emulation/emulator_setup.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cellctl::emulation {
namespace {

using config::YamlNode;

PlantConfig parse_plant(const YamlNode& n) {
  n.only_keys({"encoder_mm_per_revolution", "encoder_slip", "encoder_mount_mm"});
  PlantConfig p;
  p.encoder_mm_per_revolution =
      n.double_in_or("encoder_mm_per_revolution", 1e-6, 1e6, p.encoder_mm_per_revolution);
  p.encoder_slip = n.double_in_or("encoder_slip", -0.5, 0.5, p.encoder_slip);
  p.encoder_mount_mm = n.double_in_or("encoder_mount_mm", -1e6, 1e6, p.encoder_mount_mm);
  return p;
}

}  // namespace

// The actuators' scaling, stroke and full speed are the session's (the same keys); the rest of
// each item is the emulated actuator's physics.
scu::EmulatorConfig parse_scu_emulator(const YamlNode& section, const config::ScuSection& scu_section) {
  const auto& session = scu_section.session;
  scu::EmulatorConfig c;
  c.functions = session.functions;
  c.default_speed_percent =
      section.int_in_or<std::uint16_t>("default_speed_percent", 0, 100, c.default_speed_percent);
  for (const auto& item : section.at("actuators").items()) {
    const auto i = static_cast<std::size_t>(item.int_in<int>("index", 1, scu::kActuatorCount) - 1);
    const auto& spec = session.specs[i];
    auto& act = c.actuators[i];
    act.present = true;
    act.edges_per_mm = spec.edges_per_mm;
    auto& p = act.physics;
    p.stroke_mm = spec.stroke_mm;
    p.max_speed_mm_s = spec.full_speed_mm_s;
    p.ramp_mm_s2 = item.double_in_or("ramp_mm_s2", 0.0, 100000.0, p.ramp_mm_s2);
    p.min_speed_mm_s = item.double_in_or("min_speed_mm_s", 0.0, p.max_speed_mm_s, p.min_speed_mm_s);
    p.start_position_mm = item.double_in_or("start_position_mm", 0.0, p.stroke_mm, p.start_position_mm);
    p.scale_error = item.double_in_or("scale_error", -0.1, 0.1, p.scale_error);
  }
  return c;
}

spindle::EmulatorConfig parse_spindle_emulator(const YamlNode& section) {
  spindle::EmulatorConfig c;
  const auto block = section.maybe("emulator");
  if (!block) return c;
  const YamlNode& e = *block;
  e.only_keys({"min_hz", "max_hz", "ramp_up_hz_s", "ramp_down_hz_s", "converter_type", "firmware",
               "serial_number", "converter_hours", "motor_hours", "motor_code", "current_limit_a",
               "dc_link_voltage_v"});
  c.min_hz = e.double_in_or("min_hz", 0.0, 65535.0, c.min_hz);
  c.max_hz = e.double_in_or("max_hz", 1.0, 65535.0, c.max_hz);
  if (c.max_hz <= c.min_hz)
    (e.has("max_hz") ? e.at("max_hz") : e.at("min_hz")).fail("max_hz must be above min_hz");
  c.ramp_up_hz_s = e.double_in_or("ramp_up_hz_s", 1.0, 100000.0, c.ramp_up_hz_s);
  c.ramp_down_hz_s = e.double_in_or("ramp_down_hz_s", 1.0, 100000.0, c.ramp_down_hz_s);
  c.converter_type = e.int_in_or<std::uint16_t>("converter_type", 0, 0xFFFF, c.converter_type);
  c.firmware = e.int_in_or<std::uint16_t>("firmware", 0, 0xFFFF, c.firmware);
  c.serial_number = e.int_in_or<std::uint32_t>("serial_number", 0, 0xFFFFFFFF, c.serial_number);
  c.converter_hours = e.double_in_or("converter_hours", 0.0, 4e9, c.converter_hours);
  c.motor_hours = e.double_in_or("motor_hours", 0.0, 4e9, c.motor_hours);
  c.motor_code = e.int_in_or<std::uint8_t>("motor_code", 0, 16, c.motor_code);  // 0 inactive, M1..M16
  c.current_limit_a = e.double_in_or("current_limit_a", 0.1, 655.0, c.current_limit_a);
  c.dc_link_voltage_v = e.double_in_or("dc_link_voltage_v", 1.0, 655.0, c.dc_link_voltage_v);
  return c;
}

// The emulated encoder is the one the session expects unless the `emulator:` block says otherwise.
// Its functionality is not set here: the emulator takes the one the master's Set_Prm/Chk_Cfg choose.
encoder::EmulatorConfig parse_encoder_emulator(const YamlNode& section,
                                               const encoder::SessionConfig& session) {
  const auto block = section.maybe("emulator");
  encoder::EmulatorConfig c;
  c.address = session.station_address;
  c.line = session.bus.line;
  c.identity.physical = session.physical;
  if (!block) return c;
  const YamlNode& e = *block;
  e.only_keys({"address", "singleturn_steps", "revolutions", "serial", "state_file"});
  c.address = e.int_in_or<std::uint8_t>("address", 1, 126, session.station_address);
  c.identity.physical = config::parse_physical_resolution(e, session.physical);
  if (const auto n = e.maybe("serial")) {
    const std::string serial = n->as_string();
    if (serial.size() != 10) n->fail("must be 10 ASCII characters (manual 4.2.18)");
    std::copy(serial.begin(), serial.end(), c.identity.serial.begin());
  }
  c.state_file = e.string_or("state_file", "");
  return c;
}

EmulatorSetup parse_emulator_setup(const YamlNode& root, const config::CellConfig& cell) {
  EmulatorSetup setup;
  if (cell.scu) setup.scu = parse_scu_emulator(root.at("scu"), *cell.scu);
  if (cell.spindle) setup.spindle = parse_spindle_emulator(root.at("spindle"));
  if (cell.encoder) setup.encoder = parse_encoder_emulator(root.at("encoder"), cell.encoder->session);
  if (const auto n = root.maybe("plant")) setup.plant = parse_plant(*n);
  return setup;
}

EmulatorSetup load_emulator_setup(const config::CellConfig& cell) {
  if (!cell.document)
    throw std::invalid_argument("the cell '" + cell.name +
                                "' was made in memory: no file sets its emulators up");
  return parse_emulator_setup(*cell.document, cell);
}

}  // namespace cellctl::emulation

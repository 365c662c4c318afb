#include "config/spindle_section.hpp"

namespace cellctl::config {
namespace {

spindle::SessionConfig parse_session(const YamlNode& s) {
  spindle::SessionConfig c;
  // 20 ms: a 64-byte reply's line time.
  c.reply_timeout = s.milliseconds_or("reply_timeout_ms", 20, 2000, c.reply_timeout);
  c.retries = s.int_in_or<unsigned>("retries", 0, 10, c.retries);
  c.status_poll = s.milliseconds_or("status_poll_ms", 5, 5000, c.status_poll);
  c.values_poll = s.milliseconds_or("values_poll_ms", 5, 60000, c.values_poll);
  c.link_fault_after = s.milliseconds_or("link_fault_after_ms", 50, 60000, c.link_fault_after);
  c.set_start_parameters = s.bool_or("set_start_parameters", c.set_start_parameters);
  // A link judged dead before one request could even time out would fault on the first lost telegram.
  if (c.link_fault_after <= c.reply_timeout)
    (s.has("link_fault_after_ms") ? s.at("link_fault_after_ms") : s.at("reply_timeout_ms"))
        .fail("link_fault_after_ms must be longer than reply_timeout_ms");
  return c;
}

spindle::EmulatorConfig parse_emulator(const YamlNode& e) {
  e.only_keys({"min_hz", "max_hz", "ramp_up_hz_s", "ramp_down_hz_s", "converter_type", "firmware",
               "serial_number", "converter_hours", "motor_hours", "motor_code", "current_limit_a",
               "dc_link_voltage_v"});
  spindle::EmulatorConfig c;
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

}  // namespace

SpindleSection parse_spindle_section(const YamlNode& section) {
  section.only_keys({"reply_timeout_ms", "retries", "status_poll_ms", "values_poll_ms", "link_fault_after_ms",
                     "set_start_parameters", "emulator"},
                    kPortKeys);
  SpindleSection out;
  out.port = parse_port(section, "spindle", link::line_8n1(38400));
  out.session = parse_session(section);
  if (const auto e = section.maybe("emulator")) out.emulator = parse_emulator(*e);
  return out;
}

}  // namespace cellctl::config

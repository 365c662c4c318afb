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

}  // namespace

SpindleSection parse_spindle_section(const YamlNode& section) {
  section.only_keys({"reply_timeout_ms", "retries", "status_poll_ms", "values_poll_ms", "link_fault_after_ms",
                     "set_start_parameters", "emulator"},
                    kPortKeys);
  SpindleSection out;
  out.port = parse_port(section, "spindle", link::line_8n1(38400));
  out.session = parse_session(section);
  return out;
}

}  // namespace cellctl::config

#include "config/scu_section.hpp"

#include <string>

namespace cellctl::config {
namespace {

// actuators: [{index, edges_per_mm, stroke_mm, max_speed_mm_s, + the emulator's physics keys}]
void parse_actuators(const YamlNode& list, ScuSection& out) {
  out.session.actuators.reset();
  for (const auto& item : list.items()) {
    item.only_keys({"index", "edges_per_mm", "stroke_mm", "max_speed_mm_s"}, kScuEmulatorActuatorKeys);
    const int a = item.int_in<int>("index", 1, scu::kActuatorCount);
    const auto i = static_cast<std::size_t>(a - 1);
    if (out.session.actuators.test(i))
      item.at("index").fail("actuator " + std::to_string(a) + " is listed twice");
    out.session.actuators.set(i);
    auto& spec = out.session.specs[i];
    spec = scu::ActuatorSpec{};
    spec.edges_per_mm = item.double_in("edges_per_mm", 0.001, 1e6);
    spec.stroke_mm = item.double_in_or("stroke_mm", 1.0, 10000.0, spec.stroke_mm);
    spec.full_speed_mm_s = item.double_in_or("max_speed_mm_s", 0.1, 1000.0, spec.full_speed_mm_s);
    // SCU positions are INT32 edges: the whole stroke must fit.
    if (spec.stroke_mm * spec.edges_per_mm > 2e9)
      item.at("edges_per_mm").fail("stroke × edges_per_mm exceeds INT32");
  }
  if (out.session.actuators.none()) list.fail("lists no actuator");
}

// functions: [{id: 1..10, actuators: [..], synchronized: bool}]
void parse_functions(const YamlNode& list, ScuSection& out) {
  scu::FunctionTable table{};
  for (const auto& item : list.items()) {
    item.only_keys({"id", "actuators", "synchronized"});
    const int id = item.int_in<int>("id", 1, scu::kMotionFunctionCount);
    auto& fn = table[static_cast<std::size_t>(id - 1)];
    if (fn.defined) item.at("id").fail("function F" + std::to_string(id) + " is listed twice");
    fn.defined = true;
    const auto acts = item.at("actuators");
    for (const auto& a : acts.items()) {
      const int n = a.as_int<int>();
      if (n < 1 || n > scu::kActuatorCount || !out.session.actuators.test(static_cast<std::size_t>(n - 1)))
        a.fail("actuator " + std::to_string(n) + " is not in scu.actuators");
      fn.actuators.set(static_cast<std::size_t>(n - 1));
    }
    if (fn.actuators.none()) acts.fail("a function must move at least one actuator");
    fn.synchronized = item.bool_or("synchronized", false);
    if (fn.synchronized && fn.actuators.count() < 2)
      item.at("synchronized").fail("needs two actuators or more");
  }
  out.session.functions = table;
}

}  // namespace

ScuSection parse_scu_section(const YamlNode& section) {
  section.only_keys({"safety_id", "keepalive_ms", "reply_timeout_ms", "retries", "link_fault_after_ms",
                     "stopping_time_ms", "arrival_tolerance_edges", "default_speed_percent", "actuators", "functions"},
                    kPortKeys);
  ScuSection out;
  out.port = parse_port(section, "scu", link::line_8n1(38400));
  auto& s = out.session;
  s.safety_id = section.int_in_or<std::uint8_t>("safety_id", 0, 2, s.safety_id);
  // The SCU's watchdog is 500 ms; 0 = RC back to back, as fast as the line allows.
  s.keepalive_period = section.milliseconds_or("keepalive_ms", 0, 400, s.keepalive_period);
  s.reply_timeout = section.milliseconds_or("reply_timeout_ms", 10, 2000, s.reply_timeout);
  s.retries = section.int_in_or<int>("retries", 0, 10, s.retries);
  s.link_fault_after = section.milliseconds_or("link_fault_after_ms", 50, 60000, s.link_fault_after);
  if (s.link_fault_after <= s.reply_timeout)
    (section.has("link_fault_after_ms") ? section.at("link_fault_after_ms") : section.at("reply_timeout_ms"))
        .fail("link_fault_after_ms must be longer than reply_timeout_ms");
  s.stopping_time = section.milliseconds_or("stopping_time_ms", 0, 10000, s.stopping_time);
  s.arrival_tolerance_edges =
      section.int_in_or<std::int32_t>("arrival_tolerance_edges", 0, 100000, s.arrival_tolerance_edges);

  parse_actuators(section.at("actuators"), out);
  if (const auto f = section.maybe("functions")) {
    parse_functions(*f, out);
  } else {
    out.session.functions = scu::scp11(out.session.actuators);
  }
  return out;
}

}  // namespace cellctl::config

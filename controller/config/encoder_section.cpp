#include "config/encoder_section.hpp"

#include <chrono>
#include <limits>

namespace cellctl::config {
namespace {

using encoder::Functionality;

Functionality parse_functionality(const YamlNode& n) {
  const std::string f = n.as_choice({"class1", "class2", "scancon2.1", "scancon2.2", "scancon3.0"});
  if (f == "class1") return Functionality::class1;
  if (f == "class2") return Functionality::class2;
  if (f == "scancon2.1") return Functionality::scancon21;
  if (f == "scancon2.2") return Functionality::scancon22;
  return Functionality::scancon30;
}

encoder::EncoderParameters parse_parameters(const YamlNode& s) {
  encoder::EncoderParameters p;
  p.functionality = s.has("functionality") ? parse_functionality(s.at("functionality")) : p.functionality;
  if (const auto n = s.maybe("code_sequence"))
    p.code_sequence =
        n->as_choice({"cw", "ccw"}) == "ccw" ? encoder::CodeSequence::ccw : encoder::CodeSequence::cw;
  p.scaling = s.bool_or("scaling", p.scaling);
  p.measuring_units = s.int_in_or<std::uint32_t>("measuring_units", 1, 1u << 31, p.measuring_units);
  p.total_range = s.int_in_or<std::uint32_t>("total_range", 1, 1u << 31, p.total_range);
  if (const auto n = s.maybe("units_select")) {
    const auto u = n->as_choice({"per_revolution", "per_total_range", "per_physical_impulses"});
    p.units_select = u == "per_revolution"    ? encoder::UnitsSelect::per_revolution
                     : u == "per_total_range" ? encoder::UnitsSelect::per_total_range
                                              : encoder::UnitsSelect::per_physical_impulses;
  }
  p.commissioning = s.bool_or("commissioning", p.commissioning);
  p.short_diagnosis = s.bool_or("short_diagnosis", p.short_diagnosis);
  p.without_status_bits = s.bool_or("without_status_bits", p.without_status_bits);
  if (const auto n = s.maybe("lower_limit")) {
    p.lower_limit_enabled = true;
    p.lower_limit = static_cast<std::uint32_t>(n->as_integer_in(0, (1ll << 31) - 1));
  }
  if (const auto n = s.maybe("upper_limit")) {
    p.upper_limit_enabled = true;
    p.upper_limit = static_cast<std::uint32_t>(n->as_integer_in(1, (1ll << 31) - 1));
  }
  p.physical_impulses = s.int_in_or<std::uint32_t>("physical_impulses", 1, 1u << 31, p.physical_impulses);
  if (const auto n = s.maybe("time_base")) {
    const auto t = n->as_choice({"steps_per_s", "steps_per_100ms", "steps_per_10ms", "rpm"});
    p.time_base = t == "steps_per_s"       ? encoder::TimeBase::steps_per_s
                  : t == "steps_per_100ms" ? encoder::TimeBase::steps_per_100ms
                  : t == "steps_per_10ms"  ? encoder::TimeBase::steps_per_10ms
                                           : encoder::TimeBase::rpm;
  }
  p.endless = s.bool_or("endless", p.endless);
  if (p.without_status_bits && p.functionality != Functionality::scancon30)
    s.at("without_status_bits").fail("only with functionality scancon3.0 (manual 4.1.5 bit 4)");
  return p;
}

profibus::DpMasterConfig parse_bus(const YamlNode& s, const link::LineFormat& line) {
  profibus::DpMasterConfig b;
  b.line = line;
  b.master_address = s.int_in_or<std::uint8_t>("master_address", 0, 125, 2);
  b.slot_time_bits = s.int_in_or<std::uint32_t>("slot_time_bits", 37, 16383, b.slot_time_bits);
  b.max_retries = s.int_in_or<std::uint8_t>("retries", 0, 7, b.max_retries);
  // watchdog = 10 ms × f1 × f2: written as f1 = ms / 10, f2 = 1 (0 switches it off).
  const auto wd = s.int_in_or<unsigned>("watchdog_ms", 0, 2550, 100);
  if (wd % 10 != 0) s.at("watchdog_ms").fail("must be a multiple of 10 ms (10 ms × WD_Fact_1 × WD_Fact_2)");
  b.wd_fact_1 = static_cast<std::uint8_t>(wd / 10);
  b.wd_fact_2 = wd == 0 ? 0 : 1;
  b.data_exchange_period = s.milliseconds_or("cycle_ms", 0, 1000, std::chrono::milliseconds(1));
  b.lost_slave_time = s.milliseconds_or("lost_after_ms", 5, 60000, std::chrono::milliseconds(100));
  return b;
}

}  // namespace

encoder::PhysicalResolution parse_physical_resolution(const YamlNode& s,
                                                      encoder::PhysicalResolution fallback) {
  encoder::PhysicalResolution phys;
  phys.steps_per_revolution =
      s.int_in_or<std::uint32_t>("singleturn_steps", 2, 1u << 16, fallback.steps_per_revolution);
  phys.revolutions = s.int_in_or<std::uint32_t>("revolutions", 1, 1u << 15, fallback.revolutions);
  if (auto v = encoder::validate(phys))
    (s.has("singleturn_steps") ? s.at("singleturn_steps") : s.at("revolutions")).fail(v->describe());
  return phys;
}

EncoderSection parse_encoder_section(const YamlNode& section) {
  section.only_keys({"station_address",
                     "master_address",
                     "functionality",
                     "code_sequence",
                     "scaling",
                     "measuring_units",
                     "total_range",
                     "units_select",
                     "commissioning",
                     "short_diagnosis",
                     "without_status_bits",
                     "lower_limit",
                     "upper_limit",
                     "physical_impulses",
                     "time_base",
                     "endless",
                     "singleturn_steps",
                     "revolutions",
                     "counts_per_mm",
                     "mm_per_revolution",
                     "zero_offset_mm",
                     "preset_offset",
                     "watchdog_ms",
                     "slot_time_bits",
                     "retries",
                     "lost_after_ms",
                     "cycle_ms",
                     "emulator"},
                    kPortKeys);
  EncoderSection out;
  out.port = parse_port(section, "encoder", link::line_8e1(19200));
  auto& s = out.session;
  s.station_address = section.int_in_or<std::uint8_t>("station_address", 1, 126, 1);
  s.parameters = parse_parameters(section);
  s.physical = parse_physical_resolution(section, s.physical);
  if (auto v = encoder::validate(s.parameters, s.physical)) section.fail("parameters: " + v->describe());
  s.bus = parse_bus(section, out.port.line);
  const bool per_count = section.has("counts_per_mm");
  if (per_count == section.has("mm_per_revolution"))
    section.fail("give exactly one of counts_per_mm and mm_per_revolution");
  if (per_count)
    s.counts_per_mm = section.double_in("counts_per_mm", 1e-6, 1e9);
  else
    s.mm_per_revolution = section.double_in("mm_per_revolution", 1e-6, 1e6);
  s.zero_offset_mm = section.has("zero_offset_mm") ? section.double_in("zero_offset_mm", -1e6, 1e6) : 0.0;
  // The encoder's stored preset offset (0 until a preset): checked at every start-up against the
  // encoder's diagnosis, so that a preset made since cannot shift the positions unnoticed.
  s.expected_offset = section.int_in_or<std::int32_t>(
      "preset_offset", std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max(), 0);
  return out;
}

}  // namespace cellctl::config

#include "config/cell_limits.hpp"

namespace cellctl::config {
namespace {

StopCategory category(const YamlNode& n) {
  return static_cast<StopCategory>(n.as_integer_in(0, 2));
}

}  // namespace

CellLimits parse_cell_limits(const YamlNode& n) {
  n.only_keys({"overspeed_mm_s", "disagreement_mm", "link_silence_ms", "spindle_min_hz", "spindle_max_hz",
               "spindle_tolerance_hz"});
  CellLimits l;
  l.overspeed_mm_s = n.double_in_or("overspeed_mm_s", 0.001, 1000.0, l.overspeed_mm_s);
  l.disagreement_mm = n.double_in_or("disagreement_mm", 0.001, 1000.0, l.disagreement_mm);
  l.link_silence_ms = n.double_in_or("link_silence_ms", 10.0, 10000.0, l.link_silence_ms);
  l.spindle_min_hz = n.double_in_or("spindle_min_hz", 0.0, 100000.0, l.spindle_min_hz);
  l.spindle_max_hz = n.double_in_or("spindle_max_hz", 0.0, 100000.0, l.spindle_max_hz);
  if (l.spindle_max_hz <= l.spindle_min_hz) n.at("spindle_max_hz").fail("must be above spindle_min_hz");
  l.spindle_tolerance_hz = n.double_in_or("spindle_tolerance_hz", 0.1, 1000.0, l.spindle_tolerance_hz);
  return l;
}

StopReactions parse_stop_reactions(const YamlNode& n) {
  n.only_keys({"fault", "link", "operator", "following_error"});
  StopReactions s;
  if (auto f = n.maybe("fault")) s.fault = category(*f);
  if (auto f = n.maybe("link")) s.link = category(*f);
  if (auto f = n.maybe("operator")) s.operator_stop = category(*f);
  if (auto f = n.maybe("following_error")) s.following_error = category(*f);
  return s;
}

LoopConfig parse_loop(const YamlNode& n) {
  n.only_keys({"period_ms", "realtime", "priority", "cpu", "sample_ms"});
  LoopConfig l;
  l.period_ms = n.double_in_or("period_ms", 0.1, 100.0, l.period_ms);
  l.realtime = n.bool_or("realtime", l.realtime);
  l.priority = n.int_in_or<int>("priority", 1, 99, l.priority);
  l.cpu = n.int_in_or<int>("cpu", -1, 1023, l.cpu);
  l.sample_ms = n.double_in_or("sample_ms", l.period_ms, 10000.0, l.sample_ms);
  return l;
}

}  // namespace cellctl::config

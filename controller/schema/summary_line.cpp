#include "schema/summary_line.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "schema/json_records.hpp"

namespace cellctl::schema {
namespace {

using nlohmann::json;

const char* to_string(EndedBy::Kind k) {
  switch (k) {
    case EndedBy::Kind::link:
      return "link";
    case EndedBy::Kind::operator_stop:
      return "operator";
    case EndedBy::Kind::monitor:
      break;
  }
  return "monitor";
}

json ended_by_json(const EndedBy& e) {
  json j{{"t", round_ms(e.t)}, {"rule", e.rule}, {"kind", to_string(e.kind)}};
  if (e.kind == EndedBy::Kind::link) {
    j["device"] = e.device;
    j["symptom"] = e.symptom;
    j["since_s"] = round_ms(e.since_s);
  } else {
    j["detail"] = e.detail;
  }
  return j;
}

void put_run(json& j, const RunFigures& r) {
  json& links = j["links"];  // null for a run without a device
  for (const auto& l : r.links)
    links[l.device] = {{"replies", l.replies},
                       {"max_round_trip_ms", l.max_round_trip_ms},
                       {"max_silence_ms", l.max_silence_ms},
                       {"timeouts", l.timeouts},
                       {"retries", l.retries},
                       {"bad_frames", l.bad_frames}};
  j["cycles"] = r.cycles;
  j["overrun_cycles"] = r.overrun_cycles;
  j["missed_deadlines"] = r.missed_deadlines;
  j["jitter_p99_us"] = r.jitter_p99_us;
  j["wall_s"] = r.wall_s;
  j["mode"] = r.mode;
  j["corrections"] = r.corrections;
  if (r.teach_in)
    j["teach_in"] = {{"taught", r.teach_in->taught},
                     {"total_resolution", r.teach_in->total_resolution},
                     {"encoder_restored", r.teach_in->encoder_restored}};
  json devices = json::object();
  for (const auto& d : r.devices) devices[d.device] = {{"safe", d.safe}, {"evidence", d.evidence}};
  j["devices"] = devices;
  if (r.ended_by) j["ended_by"] = ended_by_json(*r.ended_by);
}

}  // namespace

double round_ms(double seconds) noexcept {
  return std::round(seconds * 1e3) / 1e3;
}

std::string summary_line(const SummaryLine& s) {
  json j;
  j["outcome"] = s.outcome;
  j["duration_s"] = round_ms(s.duration_s);
  j["steps"] = json::array();
  for (const auto& st : s.steps) {
    json step{
        {"label", st.label}, {"count", st.count}, {"seconds", round_ms(st.seconds)}, {"failed", st.failed}};
    if (st.interrupted) step["interrupted"] = st.interrupted;
    if (st.held_s > 0) step["held_s"] = round_ms(st.held_s);
    j["steps"].push_back(step);
  }
  j["faults"] = s.faults;
  j["event"] = "summary";
  j["journal_dropped"] = s.journal_dropped;
  if (s.run) put_run(j, *s.run);
  if (s.not_started) {
    j["outcome"] = "not started";
    j["reason"] = *s.not_started;
  }
  return j.dump();
}

std::optional<LoopFigures> loop_figures_of(const json& summary) {
  if (!summary.contains("cycles")) return std::nullopt;
  LoopFigures f;
  f.cycles = summary.value("cycles", std::uint64_t{0});
  f.jitter_p99_us = summary.value("jitter_p99_us", 0.0);
  f.overrun_cycles = summary.value("overrun_cycles", std::uint64_t{0});
  f.missed_deadlines = summary.value("missed_deadlines", std::uint64_t{0});
  f.journal_dropped = summary.value("journal_dropped", std::uint64_t{0});
  return f;
}

}  // namespace cellctl::schema

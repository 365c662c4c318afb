#include "schema/read_journal_line.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "schema/json_records.hpp"

namespace cellctl::schema {
namespace {

using nlohmann::json;

// A text field as a view of the line's own string; empty when missing or no text.
std::string_view view_of(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? std::string_view(it->get_ref<const std::string&>())
                                          : std::string_view();
}

journal::Text text_of(const json& j, const char* key) {
  return journal::Text::format("{}", view_of(j, key));
}

std::vector<double> numbers(const json& j, const char* key) {
  std::vector<double> v;
  if (const auto it = j.find(key); it != j.end() && it->is_array())
    for (const auto& x : *it) v.push_back(x.get<double>());
  return v;
}

// The step a line numbers from 1, as the event's index from 0.
std::uint32_t index_of(const json& j) {
  return static_cast<std::uint32_t>(j.value("step", 0)) - 1u;
}

// Its fields in words, "t" and "event" left out: text as it is, the rest as key=value.
std::string describe(const json& j) {
  std::string out;
  for (const auto& [k, v] : j.items()) {
    if (k == "t" || k == "event") continue;
    if (!out.empty()) out += ", ";
    out += v.is_string() ? v.get<std::string>() : fmt::format("{}={}", k, v.dump());
  }
  return out;
}

void read(const json& j, LineReader& r) {
  const double t = j.value("t", 0.0);
  const std::string_view event = view_of(j, "event");
  const auto tell = [&](journal::Payload p) { r.event({t, std::move(p)}); };
  if (event == "record") {
    r.header(header_of(j));
  } else if (event == "run_started") {
    tell(journal::RunStarted{view_of(j, "recipe"), view_of(j, "cell"), view_of(j, "mode"),
                             j.value("steps", std::uint32_t{0})});
  } else if (event == "sample") {
    SamplePoint s;
    s.t = t;
    s.planned_mm = numbers(j, "planned_mm");
    s.scu_mm = numbers(j, "scu_mm");
    s.encoder_mm = j.value("encoder_mm", 0.0);
    s.encoder_mm_s = j.value("encoder_mm_s", 0.0);
    s.spindle_set_hz = j.value("spindle_set_hz", 0.0);
    s.spindle_hz = j.value("spindle_hz", 0.0);
    r.sample(s);
  } else if (event == "step_started") {
    tell(journal::StepStarted{index_of(j), view_of(j, "label")});
  } else if (event == "step_done" || event == "step_failed") {
    tell(journal::StepEnded{index_of(j), view_of(j, "label"), event == "step_done", text_of(j, "detail")});
  } else if (event == "state") {
    tell(journal::StateChanged{view_of(j, "from"), view_of(j, "to"), text_of(j, "reason")});
  } else if (event == "command") {
    tell(journal::Command{view_of(j, "command"), text_of(j, "source")});
  } else if (event == "note") {
    r.note(t, view_of(j, "text"));
  } else if (event == "run_ended") {
    tell(journal::RunEnded{view_of(j, "outcome")});
  } else if (event == "summary") {
    r.summary(loop_figures_of(j));
  } else if (event == "fault_cleared") {
    tell(journal::FaultCleared{view_of(j, "rule")});
  } else if (event == "fault") {
    tell(journal::Fault{view_of(j, "rule"), static_cast<std::uint8_t>(j.value("category", 0)),
                        text_of(j, "detail")});
  } else if (event == "fault_injected" || event == "fault_injection_ended") {
    tell(journal::InjectedFault{view_of(j, "device"), view_of(j, "kind"), view_of(j, "spec"),
                                view_of(j, "what"), event == "fault_injection_ended",
                                j.value("still_active", false)});
  } else {
    r.other(t, event, describe(j));
  }
}

}  // namespace

void read_journal_line(std::string_view line, LineReader& reader) {
  try {
    read(json::parse(line), reader);
  } catch (const json::exception& e) {
    throw BadLine(e.what());
  }
}

}  // namespace cellctl::schema

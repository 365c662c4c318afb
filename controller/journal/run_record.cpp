#include "journal/run_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace cellctl::journal {
namespace {

using nlohmann::json;

std::vector<double> numbers(const json& j, const char* key) {
  std::vector<double> v;
  if (const auto it = j.find(key); it != j.end() && it->is_array())
    for (const auto& x : *it) v.push_back(x.get<double>());
  return v;
}

std::string text_of(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

bool operator_rule(std::string_view rule) {
  return rule == "operator_stop" || rule == "emergency_stop";
}

}  // namespace

std::string describe_event(const json& j) {
  std::string out;
  for (const auto& [k, v] : j.items()) {
    if (k == "t" || k == "event") continue;
    if (!out.empty()) out += ", ";
    out += v.is_string() ? v.get<std::string>() : fmt::format("{}={}", k, v.dump());
  }
  return out;
}

std::string_view to_string(MarkKind k) noexcept {
  switch (k) {
    case MarkKind::fault:
      return "fault";
    case MarkKind::injected_fault:
      return "injected fault";
    case MarkKind::fault_cleared:
      return "fault cleared";
    case MarkKind::command:
      return "command";
    case MarkKind::note:
      return "note";
  }
  return "?";
}

void RunRecord::add(const json& j) {
  const double t = j.value("t", 0.0);
  const std::string event = text_of(j, "event");
  if (event != "summary") end_ = std::max(end_, t);
  if (event == "record") {
    header_ = j;
  } else if (event == "run_started") {
    start_ = t;
  } else if (event == "sample") {
    SamplePoint s;
    s.t = t;
    s.planned_mm = numbers(j, "planned_mm");
    s.scu_mm = numbers(j, "scu_mm");
    s.encoder_mm = j.value("encoder_mm", 0.0);
    s.spindle_set_hz = j.value("spindle_set_hz", 0.0);
    s.spindle_hz = j.value("spindle_hz", 0.0);
    samples_.push_back(std::move(s));
  } else if (event == "step_started") {
    const int n = j.value("step", 0);
    // Started again after a hold: the step keeps its first start, so its time includes the hold.
    if (!steps_.empty() && steps_.back().step == n && steps_.back().result.empty()) return;
    close_open_steps(t, "interrupted");
    steps_.push_back({n, text_of(j, "label"), t, t, 0.0, {}, {}});
  } else if (event == "step_done" || event == "step_failed") {
    const int n = j.value("step", 0);
    if (steps_.empty() || steps_.back().step != n || !steps_.back().result.empty())
      steps_.push_back({n, text_of(j, "label"), t, t, 0.0, {}, {}});
    auto& s = steps_.back();
    s.end = t;
    s.result = event == "step_done" ? "done" : "failed";
    s.detail = text_of(j, "detail");
    if (event == "step_failed") other_failure_ = true;
  } else if (event == "state") {
    const auto to = text_of(j, "to");
    // A stop ends the step it interrupts there and then (not when the cell is at rest, maybe much later).
    if (to == "Stopping" || to == "Aborting") close_open_steps(t, "interrupted");
    if ((to == "Holding" || to == "Held") && !held_since_) held_since_ = t;
    if (to != "Holding" && to != "Held" && held_since_) {
      if (!steps_.empty() && steps_.back().result.empty()) steps_.back().held_s += t - *held_since_;
      held_since_.reset();
    }
  } else if (event == "command") {
    const auto name = text_of(j, "command");
    const auto source = text_of(j, "source");
    if (name == "start" && source != "operator") return;  // the run's own start
    if ((name == "stop" || name == "abort") && source != "monitor") operator_stop_ = true;
    marks_.push_back({t, MarkKind::command, fmt::format("{} ({})", name, source)});
  } else if (event == "note") {
    marks_.push_back({t, MarkKind::note, text_of(j, "text")});
  } else if (event == "run_ended") {
    outcome_ = text_of(j, "outcome");
    close_open_steps(t, "interrupted");
  } else if (event == "summary") {
    summary_ = j;
  } else if (event == "fault_cleared") {
    marks_.push_back({t, MarkKind::fault_cleared, text_of(j, "rule")});
  } else if (event == "fault") {
    const auto rule = text_of(j, "rule");
    if (operator_rule(rule))
      operator_stop_ = true;
    else
      other_failure_ = true;
    marks_.push_back(
        {t, MarkKind::fault,
         fmt::format("{} (category {}): {}", rule, j.value("category", 0), text_of(j, "detail"))});
  } else if (event.find("inject") != std::string::npos) {
    marks_.push_back({t, MarkKind::injected_fault, describe_event(j)});
  } else if (event.find("fault") != std::string::npos) {
    other_failure_ = true;
    marks_.push_back({t, MarkKind::fault, describe_event(j)});
  }
}

void RunRecord::close_open_steps(double t, std::string_view result) {
  for (auto& s : steps_) {
    if (!s.result.empty()) continue;
    s.end = t;
    s.result = std::string(result);
    if (held_since_) s.held_s += t - *held_since_;
  }
  held_since_.reset();
}

void RunRecord::finish() {
  close_open_steps(end_, "interrupted");
}

RunRecord RunRecord::load(const std::filesystem::path& dir_or_file) {
  const auto file = std::filesystem::is_directory(dir_or_file) ? dir_or_file / "journal.jsonl" : dir_or_file;
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the run record", file.string()));
  RunRecord r;
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.empty()) continue;
    try {
      r.add(json::parse(line));
    } catch (const json::exception& e) {
      throw std::runtime_error(fmt::format("{}:{}: not a journal line ({})", file.string(), n, e.what()));
    }
  }
  if (n == 0) throw std::runtime_error(fmt::format("{}: the run record is empty", file.string()));
  r.finish();
  return r;
}

std::vector<std::string> RunRecord::axis_names() const {
  std::vector<std::string> names;
  if (const auto it = header_.find("axes"); it != header_.end())
    for (const auto& a : *it) names.push_back(a.value("name", fmt::format("axis {}", names.size() + 1)));
  std::size_t sampled = 0;
  for (const auto& s : samples_) sampled = std::max(sampled, s.planned_mm.size());
  while (names.size() < sampled) names.push_back(fmt::format("axis {}", names.size() + 1));
  return names;
}

std::optional<std::size_t> RunRecord::measured_axis() const {
  if (const auto it = header_.find("axes"); it != header_.end())
    for (std::size_t i = 0; i < it->size(); ++i)
      if ((*it)[i].value("measured", false)) return i;
  return std::nullopt;
}

std::string RunRecord::recipe_label() const {
  if (header_.empty()) return "(a record without a header)";
  return fmt::format("{} {} ({})", header_.value("recipe", "?"), header_.value("recipe_version", "?"),
                     header_.value("recipe_file", "?"));
}

const SamplePoint* RunRecord::sample_at(double t) const noexcept {
  if (samples_.empty()) return nullptr;
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                   [](double v, const SamplePoint& s) { return v < s.t; });
  return it == samples_.begin() ? &samples_.front() : &*(it - 1);
}

std::optional<double> RunRecord::planned_s(const StepRun& s) const {
  std::string kind;
  std::optional<double> declared;
  if (const auto it = header_.find("steps");
      it != header_.end() && s.step >= 1 && static_cast<std::size_t>(s.step) <= it->size()) {
    const auto& h = (*it)[static_cast<std::size_t>(s.step - 1)];
    kind = h.value("kind", "");
    if (const auto p = h.find("planned_s"); p != h.end()) declared = p->get<double>();
  }
  if (declared) return declared;
  if (kind != "move") return std::nullopt;
  // The profile's time: from the step's start to the last sample whose planned position moved.
  const SamplePoint* prev = sample_at(s.start);
  double last_change = s.start;
  for (const auto& p : samples_) {
    if (p.t <= s.start) continue;
    if (p.t > s.end) break;
    if (prev && p.planned_mm != prev->planned_mm) last_change = p.t;
    prev = &p;
  }
  return last_change - s.start;
}

bool RunRecord::ended_by_operator() const {
  return operator_stop_ && !other_failure_ && (outcome_ == "stopped" || outcome_ == "aborted");
}

}  // namespace cellctl::journal

#include "journal/run_summary.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <map>

namespace cellctl::journal {
namespace {

// Repeated instructions carry "drill 2/3 › peck in (line 19)": summarise them under one name.
std::string summary_label(std::string_view label) {
  std::string out;
  std::size_t i = 0;
  while (i < label.size()) {
    // drop " n/m" counters
    if (label[i] == ' ' && i + 1 < label.size() && std::isdigit(static_cast<unsigned char>(label[i + 1]))) {
      std::size_t j = i + 1;
      while (j < label.size() && std::isdigit(static_cast<unsigned char>(label[j]))) ++j;
      if (j < label.size() && label[j] == '/') {
        ++j;
        while (j < label.size() && std::isdigit(static_cast<unsigned char>(label[j]))) ++j;
        i = j;
        continue;
      }
    }
    out.push_back(label[i++]);
  }
  return out;
}

}  // namespace

std::vector<RunSummary::StepTime> RunSummary::steps() const {
  std::vector<StepTime> out;  // in order of first appearance
  std::map<std::string, std::size_t> by_label;
  for (const auto& s : record_.steps()) {
    const auto label = summary_label(s.label);
    const auto [pos, fresh] = by_label.try_emplace(label, out.size());
    if (fresh) out.push_back({label, 0, 0.0, 0, 0, 0.0});
    auto& step = out[pos->second];
    ++step.count;
    step.seconds += s.seconds();
    step.held_s += s.held_s;
    if (s.result == "failed") ++step.failed;
    if (s.result == "interrupted") ++step.interrupted;
  }
  return out;
}

std::vector<std::string> RunSummary::faults() const {
  std::vector<std::string> out;
  for (const auto& m : record_.marks())
    if (m.kind == MarkKind::fault || m.kind == MarkKind::injected_fault)
      out.push_back(
          fmt::format("{:.3f}s {}{}", m.t, m.kind == MarkKind::injected_fault ? "injected: " : "", m.text));
  return out;
}

schema::SummaryLine RunSummary::line() const {
  schema::SummaryLine s;
  s.outcome = outcome();
  s.duration_s = duration_s();
  s.steps = steps();
  s.faults = faults();
  return s;
}

std::string RunSummary::to_text() const {
  std::string out = fmt::format("outcome: {} after {:.2f} s\n", outcome(), duration_s());
  for (const auto& s : steps()) {
    std::string notes;
    if (s.failed) notes += fmt::format("  ({} failed)", s.failed);
    if (s.interrupted)
      notes += fmt::format("  (interrupted by the {})", outcome() == "unfinished" ? "end" : "stop");
    if (s.held_s > 0) notes += fmt::format("  ({:.2f} s of it held)", s.held_s);
    out += fmt::format("  {:>8.2f} s  {:>3}×  {}{}\n", s.seconds, s.count, s.label, notes);
  }
  const auto f = faults();
  if (f.empty()) out += "  no faults\n";
  for (const auto& line : f) out += "  fault: " + line + "\n";
  return out;
}

}  // namespace cellctl::journal

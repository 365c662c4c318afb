#include "journal/run_summary.hpp"

#include <fmt/format.h>

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

void RunSummary::add(const Event& e) {
  end_ = std::max(end_, e.t);
  if (const auto* s = std::get_if<RunStarted>(&e.payload)) {
    (void)s;
    start_ = e.t;
  } else if (const auto* st = std::get_if<StepStarted>(&e.payload)) {
    open_[st->index] = e.t;
  } else if (const auto* en = std::get_if<StepEnded>(&e.payload)) {
    const auto it = open_.find(en->index);
    const double began = it == open_.end() ? e.t : it->second;
    if (it != open_.end()) open_.erase(it);
    const auto label = summary_label(en->label);
    auto [pos, fresh] = by_label_.try_emplace(label, steps_.size());
    if (fresh) steps_.push_back({label});
    auto& step = steps_[pos->second];
    ++step.count;
    step.seconds += e.t - began;
    if (!en->ok) ++step.failed;
  } else if (const auto* f = std::get_if<Fault>(&e.payload)) {
    faults_.push_back(
        fmt::format("{:.3f}s {} (category {}): {}", e.t, f->rule, f->category, f->detail.view()));
  } else if (const auto* r = std::get_if<RunEnded>(&e.payload)) {
    outcome_ = std::string(r->outcome);
  }
}

nlohmann::json RunSummary::to_json() const {
  nlohmann::json j;
  j["outcome"] = outcome_;
  j["duration_s"] = duration_s();
  j["steps"] = nlohmann::json::array();
  for (const auto& s : steps_)
    j["steps"].push_back(
        {{"label", s.label}, {"count", s.count}, {"seconds", s.seconds}, {"failed", s.failed}});
  j["faults"] = faults_;
  return j;
}

std::string RunSummary::to_text() const {
  std::string out = fmt::format("outcome: {} after {:.2f} s\n", outcome_, duration_s());
  for (const auto& s : steps_)
    out += fmt::format("  {:>8.2f} s  {:>3}×  {}{}\n", s.seconds, s.count, s.label,
                       s.failed ? fmt::format("  ({} failed)", s.failed) : "");
  if (faults_.empty()) out += "  no faults\n";
  for (const auto& f : faults_) out += "  fault: " + f + "\n";
  return out;
}

}  // namespace cellctl::journal

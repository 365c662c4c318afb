#include "journal/run_record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "schema/read_journal_line.hpp"

namespace cellctl::journal {
namespace {

bool operator_rule(std::string_view rule) {
  return rule == "operator_stop" || rule == "emergency_stop";
}

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

// What a record's reader is told of each line it reads back.
class RecordReader final : public schema::LineReader {
 public:
  explicit RecordReader(RunRecord& r) : r_(r) {}
  void header(const schema::RecordHeader& h) override { r_.set_header(h); }
  void event(const Event& e) override { r_.add(e); }
  void sample(const SamplePoint& s) override { r_.add_sample(s); }
  void note(double t, std::string_view text) override { r_.add_note(t, text); }
  void summary(const std::optional<schema::LoopFigures>& loop) override { r_.loop_ = loop; }
  void other(double t, std::string_view event, std::string_view description) override {
    r_.add_other(t, event, description);
  }

 private:
  RunRecord& r_;
};

std::string describe(const InjectedFault& f) {
  return fmt::format("{}, {}, {}{}, {}", f.device, f.kind, f.spec,
                     f.still_active ? ", still_active=true" : "", f.what);
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

void RunRecord::add(const Event& e) {
  const double t = e.t;
  end_ = std::max(end_, t);
  std::visit(Overloaded{
                 [&](const RunStarted&) { start_ = t; },
                 [&](const Sample& smp) { add_sample(schema::sample_point(t, smp)); },
                 [&](const StepStarted& st) {
                   const int n = static_cast<int>(st.index + 1);
                   // Started again after a hold: the step keeps its first start, so its time includes the
                   // hold.
                   if (!steps_.empty() && steps_.back().step == n && steps_.back().result.empty()) return;
                   close_open_steps(t, "interrupted");
                   steps_.push_back({n, std::string(st.label), t, t, 0.0, {}, {}});
                 },
                 [&](const StepEnded& st) {
                   const int n = static_cast<int>(st.index + 1);
                   if (steps_.empty() || steps_.back().step != n || !steps_.back().result.empty())
                     steps_.push_back({n, std::string(st.label), t, t, 0.0, {}, {}});
                   auto& s = steps_.back();
                   s.end = t;
                   s.result = st.ok ? "done" : "failed";
                   s.detail = std::string(st.detail.view());
                   if (!st.ok) other_failure_ = true;
                 },
                 [&](const StateChanged& sc) {
                   const auto to = sc.to;
                   // A stop ends the step it interrupts there and then (not when the cell is at rest, maybe
                   // much later).
                   if (to == "Stopping" || to == "Aborting") close_open_steps(t, "interrupted");
                   const bool held = to == "Holding" || to == "Held";
                   const bool hold_open = !holds_.empty() && holds_.back().to < holds_.back().from;
                   if (held && !hold_open) holds_.push_back({t, -1.0});
                   if (!held && hold_open) holds_.back().to = t;
                   if (held && !held_since_) held_since_ = t;
                   if (!held && held_since_) {
                     if (!steps_.empty() && steps_.back().result.empty())
                       steps_.back().held_s += t - *held_since_;
                     held_since_.reset();
                   }
                 },
                 [&](const Command& c) {
                   const auto source = c.source.view();
                   if (c.name == "start" && source != "operator") return;  // the run's own start
                   if ((c.name == "stop" || c.name == "abort") && source != "monitor") operator_stop_ = true;
                   marks_.push_back({t, MarkKind::command, fmt::format("{} ({})", c.name, source)});
                 },
                 [&](const Note& n) {
                   marks_.push_back({t, MarkKind::note, std::string(n.text.view())});
                 },
                 [&](const RunEnded& r) {
                   outcome_ = std::string(r.outcome);
                   close_open_steps(t, "interrupted");
                 },
                 [&](const FaultCleared& f) {
                   marks_.push_back({t, MarkKind::fault_cleared, std::string(f.rule)});
                 },
                 [&](const Fault& f) {
                   if (operator_rule(f.rule))
                     operator_stop_ = true;
                   else
                     other_failure_ = true;
                   marks_.push_back({t, MarkKind::fault,
                                     fmt::format("{} (category {}): {}", f.rule, static_cast<int>(f.category),
                                                 f.detail.view())});
                 },
                 [&](const InjectedFault& f) {
                   marks_.push_back({t, MarkKind::injected_fault, describe(f)});
                 },
             },
             e.payload);
}

void RunRecord::add_note(double t, std::string_view text) {
  end_ = std::max(end_, t);
  marks_.push_back({t, MarkKind::note, std::string(text)});
}

void RunRecord::add_sample(const SamplePoint& s) {
  end_ = std::max(end_, s.t);
  samples_.push_back(s);
}

void RunRecord::set_header(schema::RecordHeader h) {
  header_ = std::move(h);
  has_header_ = true;
}

void RunRecord::add_other(double t, std::string_view event, std::string_view description) {
  end_ = std::max(end_, t);
  // Kinds of other versions of cellctl that look like faults are kept as faults.
  if (event.find("inject") != std::string_view::npos) {
    marks_.push_back({t, MarkKind::injected_fault, std::string(description)});
  } else if (event.find("fault") != std::string_view::npos) {
    other_failure_ = true;
    marks_.push_back({t, MarkKind::fault, std::string(description)});
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
  if (!holds_.empty() && holds_.back().to < holds_.back().from) holds_.back().to = end_;
}

RunRecord RunRecord::load(const std::filesystem::path& dir_or_file) {
  const auto file = std::filesystem::is_directory(dir_or_file) ? dir_or_file / "journal.jsonl" : dir_or_file;
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the run record", file.string()));
  RunRecord r;
  RecordReader reader(r);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.empty()) continue;
    try {
      schema::read_journal_line(line, reader);
    } catch (const schema::BadLine& e) {
      throw std::runtime_error(fmt::format("{}:{}: not a journal line ({})", file.string(), n, e.what()));
    }
  }
  if (n == 0) throw std::runtime_error(fmt::format("{}: the run record is empty", file.string()));
  r.finish();
  return r;
}

std::vector<std::string> RunRecord::axis_names() const {
  std::vector<std::string> names;
  for (const auto& a : header_.axes)
    names.push_back(a.name.value_or(fmt::format("axis {}", names.size() + 1)));
  std::size_t sampled = 0;
  for (const auto& s : samples_) sampled = std::max(sampled, s.planned_mm.size());
  while (names.size() < sampled) names.push_back(fmt::format("axis {}", names.size() + 1));
  return names;
}

std::optional<std::size_t> RunRecord::measured_axis() const {
  for (std::size_t i = 0; i < header_.axes.size(); ++i)
    if (header_.axes[i].measured) return i;
  return std::nullopt;
}

std::string RunRecord::recipe_label() const {
  if (!has_header_) return "(a record without a header)";
  return fmt::format("{} {} ({})", header_.recipe.value_or("?"), header_.recipe_version.value_or("?"),
                     header_.recipe_file.value_or("?"));
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
  if (s.step >= 1 && static_cast<std::size_t>(s.step) <= header_.steps.size()) {
    const auto& h = header_.steps[static_cast<std::size_t>(s.step - 1)];
    kind = h.kind;
    declared = h.planned_s;
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

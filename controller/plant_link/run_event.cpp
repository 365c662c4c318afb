#include "plant_link/run_event.hpp"

#include "schema/journal_line.hpp"

namespace cellctl::plant_link {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

journal::Text text(std::string_view s) {
  return journal::Text::format("{}", s);
}

// As the journal's line has the value: rounded to its 0.0001, then the plant's float.
float recorded(float v) {
  return static_cast<float>(schema::recorded_value(v));
}

}  // namespace

std::optional<RunEvent> run_event_of(const journal::Event& event) {
  using Kind = RunEvent::Kind;
  RunEvent e;
  e.t = schema::recorded_time(event.t);
  const bool read = std::visit(Overloaded{
                                   [&](const journal::RunStarted& s) {
                                     e.kind = Kind::run_started;
                                     e.name = text(s.recipe);
                                     e.other = text(s.mode);
                                     e.text = text(s.job);
                                     e.step = s.steps;
                                     return true;
                                   },
                                   [&](const journal::StateChanged& s) {
                                     e.kind = Kind::state;
                                     e.name = text(s.to);
                                     e.other = text(s.from);
                                     e.text = s.reason;
                                     return true;
                                   },
                                   [&](const journal::StepStarted& s) {
                                     e.kind = Kind::step_started;
                                     e.step = s.index + 1;
                                     e.name = text(s.label);
                                     return true;
                                   },
                                   [&](const journal::StepEnded& s) {
                                     e.kind = s.ok ? Kind::step_done : Kind::step_failed;
                                     e.step = s.index + 1;
                                     e.name = text(s.label);
                                     e.text = s.detail;
                                     return true;
                                   },
                                   [&](const journal::Command& c) {
                                     e.kind = Kind::command;
                                     e.name = text(c.name);
                                     e.other = c.source;
                                     return true;
                                   },
                                   [&](const journal::Fault& f) {
                                     e.kind = Kind::fault;
                                     e.name = text(f.rule);
                                     e.category = f.category;
                                     e.text = f.detail;
                                     return true;
                                   },
                                   [&](const journal::FaultCleared& f) {
                                     e.kind = Kind::fault_cleared;
                                     e.name = text(f.rule);
                                     return true;
                                   },
                                   [&](const journal::Sample& s) {
                                     e.kind = Kind::sample;
                                     e.axes = s.axes;
                                     for (std::size_t i = 0; i < s.axes && i < journal::kMaxAxes; ++i) {
                                       e.planned_mm[i] = recorded(s.planned_mm[i]);
                                       e.scu_mm[i] = recorded(s.scu_mm[i]);
                                     }
                                     e.encoder_mm = recorded(s.encoder_mm);
                                     e.spindle_set_hz = recorded(s.spindle_set_hz);
                                     e.spindle_hz = recorded(s.spindle_actual_hz);
                                     return true;
                                   },
                                   [&](const journal::Note& n) {
                                     e.kind = Kind::note;
                                     e.text = n.text;
                                     return true;
                                   },
                                   [&](const journal::RunEnded& r) {
                                     e.kind = Kind::run_ended;
                                     e.name = text(r.outcome);
                                     return true;
                                   },
                                   [](const journal::InjectedFault&) { return false; },
                               },
                               event.payload);
  if (!read) return std::nullopt;
  return e;
}

RunEvent note_event(double t, std::string_view note) {
  RunEvent e;
  e.kind = RunEvent::Kind::note;
  e.t = schema::recorded_time(t);
  e.text = text(note);
  return e;
}

}  // namespace cellctl::plant_link

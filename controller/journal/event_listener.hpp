#pragma once
// Who hears the run's events as the journal records them: the terminal's narrator, the plant link, the
// operator page. The one typed event stream of a run (issue 24): the cycle posts events (event_sink.hpp),
// the journal's writer thread hands each to its listener as it records it — typed, never as JSON — on
// that thread, never on the cycle's.
//
// An event's names are views of strings that live as long as the run (state names, program labels): a
// listener that keeps an event, or hands it to another thread, copies it into a form of its own
// (plant_link::RunEvent).

#include <initializer_list>
#include <string_view>
#include <vector>

#include "journal/event.hpp"

namespace cellctl::journal {

class EventListener {
 public:
  virtual ~EventListener() = default;
  // Every event but notes, as recorded: its time as the journal's line has it (recorded_time()).
  virtual void on_event(const Event& e) = 0;
  // A note, whole: a note longer than one event's Text is posted in parts (NoteWriter) and heard once.
  virtual void on_note(double t, std::string_view text) = 0;
};

// Several listeners as one, each hearing every event in the order given.
class EventListeners final : public EventListener {
 public:
  EventListeners(std::initializer_list<EventListener*> listeners) {
    for (auto* l : listeners)
      if (l) listeners_.push_back(l);
  }
  void on_event(const Event& e) override {
    for (auto* l : listeners_) l->on_event(e);
  }
  void on_note(double t, std::string_view text) override {
    for (auto* l : listeners_) l->on_note(t, text);
  }

 private:
  std::vector<EventListener*> listeners_;
};

}  // namespace cellctl::journal

#pragma once
// Where the cycle's events go: the Journal in a run, a recording fake in tests.

#include <fmt/format.h>

#include <cstddef>
#include <iterator>
#include <string_view>

#include "journal/event.hpp"

namespace cellctl::journal {

class EventSink {
 public:
  virtual ~EventSink() = default;
  // Cycle side: must not allocate, lock or do I/O.
  virtual void post(double t, const Payload& payload) noexcept = 0;
};

// Posts a note of any length, never cut: as many Note events as it takes, every one but the last
// `continued`. Allocation-free: formatted straight into the events' fixed buffers.
class NoteWriter {
 public:
  NoteWriter(EventSink& sink, double t) noexcept : sink_(sink), t_(t) {}
  NoteWriter(const NoteWriter&) = delete;
  NoteWriter& operator=(const NoteWriter&) = delete;
  ~NoteWriter() { sink_.post(t_, note_); }  // the last part (the only one of a short note)

  void put(char c) noexcept {
    if (note_.text.size == note_.text.chars.size()) {
      note_.continued = true;
      sink_.post(t_, note_);
      note_ = Note{};
    }
    note_.text.chars[note_.text.size++] = c;
  }
  // An output iterator for fmt::format_to.
  struct Out {
    using iterator_category = std::output_iterator_tag;
    using value_type = void;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = void;
    NoteWriter* w;
    Out& operator=(char c) noexcept {
      w->put(c);
      return *this;
    }
    Out& operator*() noexcept { return *this; }
    Out& operator++() noexcept { return *this; }
    Out operator++(int) noexcept { return *this; }
  };
  [[nodiscard]] Out out() noexcept { return Out{this}; }

 private:
  EventSink& sink_;
  double t_;
  Note note_;
};

inline void post_note(EventSink& sink, double t, std::string_view text) noexcept {
  NoteWriter w(sink, t);
  for (const char c : text) w.put(c);
}

template <class... Args>
void post_note(EventSink& sink, double t, fmt::format_string<Args...> format, Args&&... args) {
  NoteWriter w(sink, t);
  fmt::format_to(w.out(), format, std::forward<Args>(args)...);
}

}  // namespace cellctl::journal

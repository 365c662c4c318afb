#pragma once
// The run record's event lines (journal.jsonl), one JSON object per line: {"t": 1.234, "event":
// "step_started", …}. Written here from the typed events; read back by read_journal_line.hpp. The one
// place that knows their keys.
//
// What a line records is rounded (recorded_time, recorded_value), so that a record read back holds
// exactly what the run held when it wrote it: whoever keeps an event of the run in-process rounds the
// same way (the journal's RunRecord, the plant's RunEvent).

#include <string>
#include <string_view>
#include <vector>

#include "journal/event.hpp"

namespace cellctl::schema {

// A line's time: the run's seconds to the microsecond.
[[nodiscard]] double recorded_time(double t) noexcept;
// A sample's value (mm, mm/s, Hz) to the nearest 0.0001, not as the float's binary expansion
// (12.300000190734863), which no reader wants and which triples the file.
[[nodiscard]] double recorded_value(float v) noexcept;

// A sample as its line records it.
struct SamplePoint {
  double t = 0.0;
  std::vector<double> planned_mm;  // per axis
  std::vector<double> scu_mm;      // per axis
  double encoder_mm = 0.0;         // of the measured axis, if there is one
  double encoder_mm_s = 0.0;
  double spindle_set_hz = 0.0;
  double spindle_hz = 0.0;
};
[[nodiscard]] SamplePoint sample_point(double t, const journal::Sample& s);

// The line of an event (a note's `text` is the note's whole text, whatever the event holds).
[[nodiscard]] std::string event_line(const journal::Event& e);
[[nodiscard]] std::string note_line(double t, std::string_view text);

}  // namespace cellctl::schema

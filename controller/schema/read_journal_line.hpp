#pragma once
// A journal line read back (`cellctl report`, `cellctl compare`, the plots of a record on disk): what
// the line is, told to a LineReader as the typed records the run wrote it from. Lenient as a reader of
// records written by other versions must be: a missing key reads as its default, a line of a kind it
// does not know is told as other() with its fields in words.

#include <optional>
#include <stdexcept>
#include <string_view>

#include "journal/event.hpp"
#include "schema/journal_line.hpp"
#include "schema/record_header.hpp"
#include "schema/summary_line.hpp"

namespace cellctl::schema {

class LineReader {
 public:
  virtual ~LineReader() = default;
  virtual void header(const RecordHeader& h) = 0;
  // Any event but a sample or a note, its time as recorded. Its views live for the call only; a text
  // longer than a journal::Text (never one this program wrote) is cut to it.
  virtual void event(const journal::Event& e) = 0;
  virtual void sample(const SamplePoint& s) = 0;
  virtual void note(double t, std::string_view text) = 0;
  // The summary line; `loop`: its loop figures (none when the run did not end normally).
  virtual void summary(const std::optional<LoopFigures>& loop) = 0;
  // A line of another kind (`event`, maybe empty), its fields but t and event in words: "key=value"
  // for those that are no text.
  virtual void other(double t, std::string_view event, std::string_view description) = 0;
};

// Not a JSON object of the journal's keys: the parser's words.
struct BadLine : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws BadLine.
void read_journal_line(std::string_view line, LineReader& reader);

}  // namespace cellctl::schema

#pragma once
// The page's run history (GET /runs), typed, and its JSON; and what it reads of a run record to make
// it: the recipe from the record's first line, how the run ended from its last. Lenient as a reader of
// records written by other versions must be: a line that is not the one looked for reads as none, a
// missing key as its default.
//
// {"runs":[{"run":"short-20261128-050327-job3","recipe":"short","outcome":"complete","duration_s":5.5,
//   "plot":true,"devices":[{"name":"scu","safe":"observed","evidence":"…"}]}],"more":false}
// A run still being written, or cut short, has no summary: "outcome":null.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "schema/summary_line.hpp"

namespace cellctl::schema {

struct RunEntry {
  std::string run;                    // the record's folder name
  std::optional<std::string> recipe;  // from its header line
  struct Ended {                      // from its summary line
    std::string outcome;
    double duration_s = 0.0;
    std::vector<DeviceVerdict> devices;  // in the summary's order of names
  };
  std::optional<Ended> ended;
  bool plot = false;  // its plot.html is there
};

struct RunHistory {
  std::vector<RunEntry> runs;  // newest first
  bool more = false;           // more records than listed
};

[[nodiscard]] std::string run_history_json(const RunHistory& history);

// The recipe a record's header line names; nullopt when the line is no header.
[[nodiscard]] std::optional<std::string> header_recipe(std::string_view line);
// How a run ended, from its summary line; nullopt when the line is no summary.
[[nodiscard]] std::optional<RunEntry::Ended> summary_end(std::string_view line);

}  // namespace cellctl::schema
